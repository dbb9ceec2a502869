// Walks the glTF node hierarchy, emitting every mesh instance in world space and the first
// perspective camera.
#pragma once

#include <string>

#include "runtime/scene/scene.h"

namespace tinygltf {
class Model;
}

namespace cohort::gltf {

// Expects convert_materials() to have filled scene.materials already.
void emit_default_scene(const tinygltf::Model& model, const std::string& file, Scene& scene);

}  // namespace cohort::gltf
