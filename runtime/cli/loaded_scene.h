// A scene loaded once and rendered many times: what the Python module drives. The devices stay open
// with the scene uploaded and their programs built, the file is read once, and each tree (the BVH,
// or the KD-tree pth and hash walk) is built once; each render's options are `cohort render`'s,
// parsed and checked the same way, so a render here equals the CLI's with the same options bit
// for bit.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "runtime/cli/render_steps.h"

namespace cohort {

// One render of a loaded scene.
struct SceneRender {
  Image image;                    // mean radiance per pixel, linear RGB
  std::optional<AovImages> aovs;  // with --aov or --denoise
  std::optional<Image> denoised;  // with --denoise
  nlohmann::json stats;           // what --stats writes, with "setup": what this render set up
  bool interrupted = false;       // stopped by the hooks before its samples
};

class LoadedScene {
 public:
  // `base`: the scene, and the options every render of it shares (--device, --backend, --tree,
  // --tree-budget, --memory-limit, --no-cache). Opens the devices and loads the file; the tree is
  // built by the first render that needs it.
  explicit LoadedScene(RenderCommand base);
  LoadedScene(const LoadedScene&) = delete;
  LoadedScene& operator=(const LoadedScene&) = delete;

  // Renders the scene with `command`'s other options (its shared ones must equal the
  // base's: InputError otherwise); `camera`, when given, replaces the scene's camera (before
  // --camera-bounds and --fov). `denoise_venvs`: where else the pyoidn wheel may be.
  SceneRender render(const RenderCommand& command, const std::optional<SceneCamera>& camera,
                       const RenderHooks& hooks, const std::vector<std::filesystem::path>& denoise_venvs = {});

  // What `cohort info` prints, as JSON: triangles, bounds, materials, lights, camera, the tree and
  // its device bytes (the tree of --method auto).
  nlohmann::json info();

  const std::vector<DeviceInfo>& devices() const { return devices_; }

 private:
  // The scene as a render needs it: its tree (the KD-tree or not), the white sky, an environment
  // map; `camera` is its own, before each render's.
  using VariantKey = std::tuple<bool, bool, std::string>;
  struct Variant {
    std::unique_ptr<PreparedRender> render;  // at a fixed address: the pool knows its scene by it
    SceneCamera camera;
  };
  // The variant of `plan`, made (and its tree built: `built`) on first use.
  Variant& variant(const RenderPlan& plan, bool& built);

  RenderCommand base_;
  std::vector<DeviceInfo> devices_;
  std::shared_ptr<DevicePool> pool_;
  ProgramCache cache_;
  Scene loaded_;
  double load_seconds_ = 0;
  std::map<bool, PreparedScene> trees_;  // by whether the KD-tree is needed
  std::map<VariantKey, Variant> variants_;
  std::uint32_t renders_ = 0;
};

}  // namespace cohort
