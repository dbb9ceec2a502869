// Finds files named inside scene files (material libraries, textures), which are often written on
// case-insensitive systems: "KAMEN.JPG" in the .mtl, "kamen.jpg" on disk.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace cohort {

// `name` relative to `dir` (backslashes read as separators), matched exactly first and then one
// path component at a time ignoring letter case.
std::optional<std::filesystem::path> find_file(const std::filesystem::path& dir, const std::string& name);

}  // namespace cohort
