// glTF metallic-roughness materials (with the emissive-strength, transmission and ior extensions)
// to SceneMaterial, decoding the base-colour and emissive images they use into Scene::textures.
#pragma once

#include <string>

#include "runtime/scene/scene.h"

namespace tinygltf {
class Model;
}

namespace cohort::gltf {

// How messages and `info` name image `index` of the model: its file name, or "image N" for an image
// in a buffer view or a data URI (which would quote the whole image).
std::string image_name(const tinygltf::Model& model, int index);

// Appends one SceneMaterial per glTF material, in order, so glTF material i is scene material i.
void convert_materials(const tinygltf::Model& model, const std::string& file, Scene& scene);

}  // namespace cohort::gltf
