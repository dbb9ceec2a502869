#include "runtime/scene/texture_decode.h"

#include <climits>
#include <cstdint>
#include <cstring>

#include <tiny_gltf.h>

namespace cohort {
namespace {

// tinygltf keeps 16-bit PNGs at 16 bits; the renderer's textures are 8-bit.
std::vector<std::uint8_t> to_rgba8(const tinygltf::Image& image) {
  const std::size_t texels = static_cast<std::size_t>(image.width) * image.height;
  if (image.bits == 8) return {image.image.begin(), image.image.begin() + texels * 4};
  std::vector<std::uint8_t> rgba(texels * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    std::uint16_t v;
    std::memcpy(&v, image.image.data() + 2 * i, 2);
    rgba[i] = static_cast<std::uint8_t>(v >> 8);
  }
  return rgba;
}

}  // namespace

std::optional<Texture> decode_texture(std::string name, const unsigned char* bytes, std::size_t size,
                                      std::string* error) {
  if (size == 0 || size > static_cast<std::size_t>(INT_MAX)) {
    *error = "empty or oversized image data";
    return std::nullopt;
  }
  tinygltf::Image image;
  std::string warn;
  // tinygltf's stb_image decoder, forced to 4 channels (its default option).
  if (!tinygltf::LoadImageData(&image, 0, error, &warn, 0, 0, bytes, static_cast<int>(size), nullptr))
    return std::nullopt;
  const std::size_t expected = static_cast<std::size_t>(image.width) * image.height * 4 * (image.bits / 8);
  if (image.component != 4 || (image.bits != 8 && image.bits != 16) || image.image.size() < expected) {
    *error = "unexpected decoded image layout";
    return std::nullopt;
  }
  Texture texture{.name = std::move(name), .width = image.width, .height = image.height};
  texture.rgba = to_rgba8(image);
  return texture;
}

}  // namespace cohort
