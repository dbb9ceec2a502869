#pragma once

#include <filesystem>
#include <string>

namespace cohort {

struct OutputPaths {
  std::filesystem::path exr;
  std::filesystem::path png;
  std::filesystem::path checkpoint;  // --checkpoint / --resume
  std::filesystem::path denoised_exr, denoised_png;  // --denoise
};

// "-o NAME", "NAME.exr" or "NAME.png" -> both paths; empty -> the scene's stem in the current
// directory. Throws InputError for another extension or a directory that does not exist.
OutputPaths output_paths(const std::string& output, const std::filesystem::path& scene);

}  // namespace cohort
