// Fuzz builds only: the implementations of tinygltf, tinyobjloader and stb_image compiled from their
// Debian headers into the fuzz targets, so that the parsers the loaders hand untrusted bytes to are
// instrumented too (coverage guidance, ASan, UBSan). The normal build links Debian's shared
// libraries instead.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>
