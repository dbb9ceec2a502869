// glTF metallic-roughness materials (with the emissive-strength, transmission and ior extensions)
// to SceneMaterial, decoding the base-colour and emissive images they use into Scene::textures.
#pragma once

#include <string>

#include "runtime/scene/scene.h"

namespace tinygltf {
class Model;
}

namespace cohort::gltf {

// Appends one SceneMaterial per glTF material, in order, so glTF material i is scene material i.
void convert_materials(const tinygltf::Model& model, const std::string& file, Scene& scene);

}  // namespace cohort::gltf
