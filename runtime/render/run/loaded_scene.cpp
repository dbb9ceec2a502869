#include "runtime/render/run/loaded_scene.h"

#include <chrono>

#include "runtime/render/workloads.h"

namespace cohort {

LoadedScene::LoadedScene(const RenderInput& base, FirstTree first_tree)
    : first_tree_(std::move(first_tree)),
      opened_(open_render_devices(base, 0)),
      cache_(base.program_cache ? std::optional(ProgramCache::default_directory()) : std::nullopt),
      path_(base.scene) {
  const auto t0 = std::chrono::steady_clock::now();
  loaded_ = load_scene(path_);
  load_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

LoadedScene::Variant& LoadedScene::variant(const RenderInput& input, bool& built) {
  const TreeKey tree_key{input.needs_kdtree(), input.sorts()};
  const VariantKey key{tree_key, input.white_sky, input.environment_map.string()};
  built = false;
  if (auto it = variants_.find(key); it != variants_.end()) return it->second;
  auto tree = trees_.find(tree_key);
  if (tree == trees_.end()) {
    PreparedScene prepared = build_render_trees(input, opened_.devices, [&](const TreeChoice& choice) {
      return prepare_loaded_scene(path_, loaded_, choice);
    });
    if (trees_.empty() && first_tree_) first_tree_(prepared);
    tree = trees_.emplace(tree_key, std::move(prepared)).first;
    built = true;
  }
  PreparedScene scene = tree->second;
  RenderInput scene_input = input;  // its settings are each render's own
  apply_scene_options(scene, scene_input);
  const SceneCamera camera = scene.camera;
  auto render = std::make_unique<PreparedRender>(PreparedRender{.input = std::move(scene_input),
                                                                .devices = opened_.devices,
                                                                .pool = opened_.pool,
                                                                .scene = std::move(scene),
                                                                .cache = cache_});
  return variants_.emplace(key, Variant{std::move(render), camera}).first->second;
}

LoadedScene::Prepared LoadedScene::prepare(const RenderInput& input, const std::optional<SceneCamera>& camera) {
  RenderInput render_input = input;
  if (render_input.white_sky) apply_white_sky_settings(render_input.settings);
  bool built = false;
  Variant& v = variant(render_input, built);
  PreparedRender& render = *v.render;
  render.input = std::move(render_input);
  render.scene.camera = render_camera(camera ? *camera : v.camera, render.scene.scene.bounds(), render.input);
  return {render, built};
}

const PreparedScene& LoadedScene::scene(const RenderInput& input) {
  bool built = false;
  return variant(input, built).render->scene;
}

}  // namespace cohort
