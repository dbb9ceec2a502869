// One function per subcommand; each returns the exit code or throws.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "runtime/render/render_settings.h"

namespace cohort {

struct RenderCommand {
  std::filesystem::path scene;
  std::string output;  // base name or .exr/.png path; empty: the scene's stem in the current directory
  std::string resolution = "512x512";
  std::string device;
  std::string backend = "opencl";  // opencl | cuda
  std::string stats_file;
  std::string environment;  // "R,G,B" or one value
  std::string camera_bounds;  // "ex,ey,ez,tx,ty,tz": fractions of the scene bounds
  float fov = 0;              // vertical field of view in degrees; 0 = the camera's own
  double memory_limit_mib = 0;  // pretend the device has at most this much memory (tests, sharing)
  double tree_budget_mib = 0;   // KD-tree bytes (nodes, leaf lists, triangles); 0: the fastest tree
  std::string tree = "auto";    // --tree: auto, deep or compact (tree_options)
  bool white_sky = false;
  double checkpoint_seconds = 0;  // --checkpoint: save the film this often
  bool checkpoint = false;        // --checkpoint given
  bool resume = false;
  bool verbose = false;
  bool no_cache = false;
  std::string aov;        // --aov: comma list of albedo, normal, depth
  bool denoise = false;   // --denoise: also write OUT.denoised.exr/.png (Open Image Denoise)
  std::optional<std::string> target_error;  // --target-error: adaptive sampling (checked in parse_render)
  RenderSettings settings;
};

struct BenchCommand {
  std::vector<std::filesystem::path> scenes;
  std::string resolution = "512";        // path tracing: square image side
  std::string trace_resolution = "1024";  // protocol rays: square image side
  std::uint32_t spp = 4;
  unsigned reps = 3;
  std::string methods = "all";  // comma list, "all" or "none"
  std::string views = "exterior";
  std::string camera_bounds;  // an extra "custom" view
  float fov = 0;
  SortSettings sort;  // render's defaults
  std::string device;
  std::string backend = "opencl";  // opencl | cuda
  std::string tree = "auto";       // --tree, as render's
  std::string json;
  bool no_traversal = false;
  bool gate = false;     // the ordering gate experiment instead of the usual figures
  unsigned bounces = 3;  // gate: bounces to measure
};

// A utility for the benchmark scripts: a scene's world-space triangles as a PLY soup, optionally
// subdivided (each level 4x the triangles).
struct ExportCommand {
  std::filesystem::path scene;
  std::filesystem::path output;
  unsigned subdivide = 0;
  unsigned copies = 1;  // side by side along z, after subdividing
};

int run_render(const RenderCommand& cmd);
int run_bench(const BenchCommand& cmd);
int run_export(const ExportCommand& cmd);
int run_info(const std::filesystem::path& scene, const std::string& tree);
int run_devices();

// Straggler rays from a render's --stats (--stragglers), traced again on the host.
struct ReplayCommand {
  std::filesystem::path scene;
  std::filesystem::path stats;
};
int run_replay(const ReplayCommand& cmd);

}  // namespace cohort
