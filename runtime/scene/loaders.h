// Format readers behind load_scene(). Each gets the bytes already read (and inflated) and the path
// for messages and relative references; each returns geometry and materials only, load_scene()
// applies the checks common to every format.
#pragma once

#include <filesystem>
#include <string>

#include "runtime/scene/scene.h"

namespace cohort {

Scene load_gltf(const std::filesystem::path& path, const std::string& bytes, bool binary);
Scene load_obj(const std::filesystem::path& path, const std::string& text);
Scene load_ply(const std::filesystem::path& path, const std::string& bytes);

}  // namespace cohort
