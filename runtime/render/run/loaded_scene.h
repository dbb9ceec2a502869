// A scene loaded once and rendered many times: what the Python module drives. The devices stay open
// with the scene uploaded and their programs built, the file is read once, and each tree (the BVH,
// the 4-wide one hash and pth walk where --tree auto gives the others the 8-wide one, or the KD-tree)
// is built once from the loaded scene; a white sky or an
// environment map makes a variant of the scene's tables (uploaded when first used), and a camera is
// set per render. Each render runs as any other (render_run.h).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "runtime/render/run/render_prepare.h"

namespace cohort {

class LoadedScene {
 public:
  // Called with the scene's first tree once it is built (its load warnings are the scene's).
  using FirstTree = std::function<void(const PreparedScene&)>;

  // `base`: the scene, and what every render of it shares (the devices, the tree, the program
  // cache, the memory limit). Opens the devices and loads the file; the tree is built by the first
  // render that needs it.
  LoadedScene(const RenderInput& base, FirstTree first_tree = {});
  LoadedScene(const LoadedScene&) = delete;
  LoadedScene& operator=(const LoadedScene&) = delete;

  // The scene ready for `input` (whose scene, devices and tree are the base's: the caller checks),
  // its camera `camera` when given, else the scene's own, then input's camera_bounds and fov. The
  // render stays valid and at its address (the pool knows its scene by it) until the next call.
  struct Prepared {
    PreparedRender& render;
    bool built_tree = false;  // this call built a tree
  };
  Prepared prepare(const RenderInput& input, const std::optional<SceneCamera>& camera);

  // The scene as `input` renders it, without its camera options (what `info` describes).
  const PreparedScene& scene(const RenderInput& input);

  const std::vector<DeviceInfo>& devices() const { return opened_.devices; }
  double load_seconds() const { return load_seconds_; }

 private:
  // Which tree a render needs: whether it needs the KD-tree, and whether hash or pth runs (on CPUs
  // --tree auto then builds the 4-wide BVH, else the 8-wide one; tree_options).
  using TreeKey = std::pair<bool, bool>;
  // The scene as a render needs it: its tree, the white sky, an environment map; `camera` is its
  // own, before each render's.
  using VariantKey = std::tuple<TreeKey, bool, std::string>;
  struct Variant {
    std::unique_ptr<PreparedRender> render;  // at a fixed address: the pool knows its scene by it
    SceneCamera camera;
  };
  // The variant of `input`, made (and its tree built: `built`) on first use.
  Variant& variant(const RenderInput& input, bool& built);

  FirstTree first_tree_;
  OpenedDevices opened_;
  ProgramCache cache_;
  std::filesystem::path path_;
  Scene loaded_;
  double load_seconds_ = 0;
  std::map<TreeKey, PreparedScene> trees_;
  std::map<VariantKey, Variant> variants_;
};

}  // namespace cohort
