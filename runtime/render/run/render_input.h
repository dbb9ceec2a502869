// What one render run takes, checked already: the scene and what changes it, the devices and the
// tree they trace, the settings, what to make beside the image and how the film is saved.
// `cohort render` and the Python module parse their options into one (runtime/cli/render_parse.cpp);
// `cohort bench` fills its own. The run (render_run.h) reads nothing else: the checkpoint's
// fingerprint, the devices opened, the trees built.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "runtime/backend/device.h"
#include "runtime/render/render_settings.h"
#include "runtime/render/run/aov.h"

namespace cohort {

// How the film is saved and resumed (--checkpoint, --resume); the file is the caller's.
struct CheckpointPolicy {
  bool save = false;    // save every `seconds` (0: only at the end) and when the render ends
  bool resume = false;  // continue from the file when it holds this render's film (and save at the end)
  double seconds = 0;
  bool any() const { return save || resume; }
};

struct RenderInput {
  std::filesystem::path scene;
  RenderSettings settings;  // the image size and --env's colour parsed; the white sky's are added when prepared

  // the devices
  Backend backend = Backend::opencl;
  std::string device;              // --device: as select_devices takes it (CUDA: an index or a name)
  std::uint64_t memory_limit = 0;  // bytes the devices may use; 0: all they have
  bool program_cache = true;       // read and write the kernel binary cache (--no-cache: false)

  // the tree (tree_options)
  std::string tree = "auto";
  double tree_budget_mib = 0;  // KD-tree bytes (nodes, leaf lists, triangles); 0: the fastest tree

  // what changes the scene as loaded
  std::filesystem::path environment_map;  // --env FILE.exr; empty: none (a constant is in the settings)
  bool white_sky = false;
  std::optional<std::array<float, 6>> camera_bounds;  // eye and target at fractions of the scene bounds
  float fov = 0;                                      // vertical degrees; 0: the camera's own

  // beside the image
  AovSelection aovs;     // --aov: first-hit AOVs written to the EXR
  bool denoise = false;  // --denoise: the first-hit albedo and normal guide the denoiser
  CheckpointPolicy checkpoint;

  bool runs_sorting_methods = false;  // `cohort bench`: hash or pth is among the methods it runs on the scene

  // --tree-budget and --speculative ask for the KD-tree
  bool needs_kdtree() const { return tree_budget_mib > 0 || settings.speculative; }
  // hash or pth runs: they walk the top of the KD-tree or the 4-wide BVH, so auto builds no 8-wide one
  bool sorts() const { return settings.method == "hash" || settings.method == "pth" || runs_sorting_methods; }
  bool first_hit_aovs() const { return aovs.any() || denoise; }
  std::size_t pixels() const { return std::size_t(settings.width) * settings.height; }
};

}  // namespace cohort
