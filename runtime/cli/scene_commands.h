// The Python module's renders of a loaded scene (runtime/render/run/loaded_scene.h) by `cohort
// render`'s options: each render's options parsed and checked as the command line's, the run the
// command line's, its figures written as --stats writes them, so a render here equals the CLI's
// with the same options bit for bit.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <vector>

#include "runtime/cli/render_steps.h"
#include "runtime/render/run/loaded_scene.h"

namespace cohort {

// One render of a loaded scene.
struct SceneRender {
  Image image;                    // mean radiance per pixel, linear RGB
  std::optional<AovImages> aovs;  // with --aov or --denoise
  std::optional<Image> denoised;  // with --denoise
  nlohmann::json stats;           // what --stats writes, with "setup": what this render set up
  bool interrupted = false;       // stopped by the hooks before its samples
};

class SceneCommands {
 public:
  // `base`: the scene, and the options every render of it shares (--device, --backend, --tree,
  // --tree-budget, --memory-limit, --no-cache). Opens the devices and loads the file; the tree is
  // built by the first render that needs it.
  explicit SceneCommands(RenderCommand base);
  SceneCommands(const SceneCommands&) = delete;
  SceneCommands& operator=(const SceneCommands&) = delete;

  // Renders the scene with `command`'s other options (its shared ones must equal the
  // base's: InputError otherwise); `camera`, when given, replaces the scene's camera (before
  // --camera-bounds and --fov). `denoise_venvs`: where else the pyoidn wheel may be.
  SceneRender render(const RenderCommand& command, const std::optional<SceneCamera>& camera,
                     const RenderHooks& hooks, const std::vector<std::filesystem::path>& denoise_venvs = {});

  // What `cohort info` prints, as JSON: triangles, bounds, materials, lights, camera, the tree and
  // its device bytes (the tree of --method auto).
  nlohmann::json info();

  const std::vector<DeviceInfo>& devices() const { return scene_.devices(); }

 private:
  RenderCommand base_;
  LoadedScene scene_;
  std::uint32_t renders_ = 0;
};

}  // namespace cohort
