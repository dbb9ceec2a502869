// One function per subcommand; each returns the exit code or throws.
#pragma once

#include <filesystem>
#include <string>

#include "runtime/render/render_settings.h"

namespace cohort {

struct RenderCommand {
  std::filesystem::path scene;
  std::string output;  // base name or .exr/.png path; empty: the scene's stem in the current directory
  std::string resolution = "512x512";
  std::string device;
  std::string stats_file;
  std::string environment;  // "R,G,B" or one value
  bool verbose = false;
  bool no_cache = false;
  RenderSettings settings;
};

int run_render(const RenderCommand& cmd);
int run_info(const std::filesystem::path& scene);
int run_devices();

}  // namespace cohort
