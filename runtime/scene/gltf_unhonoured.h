// Names what a glTF file asks for that the loader does not honour, so that no part of a material is
// dropped silently: one warning per feature with the number of materials that use it, and a note
// for what a path tracer deliberately leaves out (ambient occlusion maps).
#pragma once

#include <string>

#include "runtime/scene/scene.h"

namespace tinygltf {
class Model;
}

namespace cohort::gltf {

// Appends the warnings and notes to `scene`; `file` prefixes each. Optional extensions that no
// material carries (and that the loader does not implement) are named in one warning of their own.
void report_unhonoured(const tinygltf::Model& model, const std::string& file, Scene& scene);

// After the geometry is in: names the textures of materials whose coordinate set no primitive has.
void report_missing_coordinates(const std::string& file, Scene& scene);

// Whether the loader implements a glTF extension (so extensionsRequired may name it).
bool extension_implemented(const std::string& name);

}  // namespace cohort::gltf
