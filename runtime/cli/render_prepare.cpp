#include <fmt/format.h>

#include <algorithm>

#include "runtime/backend/device_choice.h"
#include "runtime/backend/open_device.h"
#include "runtime/cli/parse_values.h"
#include "runtime/cli/render_steps.h"
#include "runtime/render/scene/environment_map.h"
#include "runtime/render/methods/methods.h"
#include "runtime/render/scene/scene_memory.h"
#include "runtime/render/workloads.h"

namespace cohort {

OpenedDevices open_render_devices(const RenderPlan& plan, int local_rank) {
  const std::uint64_t limit = plan.memory_limit;
  if (plan.backend == Backend::opencl) {
    std::vector<DeviceInfo> devices = select_devices(list_backend_devices(Backend::opencl), plan.command.device, local_rank);
    if (limit) {
      for (auto& device : devices) {
        device.global_memory = std::min(device.global_memory, limit);
        device.max_allocation = std::min(device.max_allocation, limit);
      }
    }
    auto pool = std::make_shared<DevicePool>(devices, opencl_opener(devices));
    return {std::move(devices), std::move(pool)};
  }
  // CUDA renders on one GPU per process (several through MPI ranks); opened here once so a missing
  // GPU is an error before the scene loads, and again on the pool's thread that uses it
  const Backend backend = plan.backend;
  std::vector<DeviceInfo> devices{open_device(backend, plan.command.device, limit)->info()};
  auto pool = std::make_shared<DevicePool>(
      devices, [backend, spec = plan.command.device, limit](std::size_t) { return open_device(backend, spec, limit); });
  return {std::move(devices), std::move(pool)};
}

PreparedScene build_render_trees(const RenderPlan& plan, const std::vector<DeviceInfo>& devices,
                                 const std::function<PreparedScene(const TreeChoice&)>& build) {
  const RenderCommand& cmd = plan.command;
  // what rays are traced through (tree_options: the BVH unless a tree budget or speculative traversal
  // asks for the KD-tree, which then fits the devices); any gives the same image
  const TreeChoice tree = tree_options(cmd.tree, devices, cmd.tree_budget_mib > 0 || plan.settings().speculative);
  PreparedScene prepared = build(tree);
  // the BVH has no depth to trade for bytes: where it does not fit, auto falls back to the KD-tree
  if (plan.memory_limit && prepared.bvh4 && cmd.tree == "auto" &&
      scene_memory(prepared.tree, prepared.tables, prepared.bvh()).total() > plan.memory_limit)
    prepared = build(TreeChoice{tree.kd, false});
  if (cmd.tree_budget_mib > 0)
    prepared.tree = build_kdtree_within(prepared.scene.positions, tree.kd,
                                        static_cast<std::size_t>(cmd.tree_budget_mib * 1048576.0));
  if (plan.memory_limit) fit_scene_to(prepared, plan.memory_limit, tree.kd);
  return prepared;
}

void apply_scene_options(PreparedScene& prepared, RenderPlan& plan) {
  if (plan.environment_map) set_environment_map(prepared.tables, load_environment_map(plan.command.environment));
  if (plan.command.white_sky) apply_white_sky(prepared, plan.command.settings);
}

void apply_render_options(PreparedScene& prepared, RenderPlan& plan) {
  apply_scene_options(prepared, plan);
  prepared.camera = plan_camera(prepared.camera, prepared.scene.bounds(), plan.command);
}

SceneCamera plan_camera(SceneCamera camera, const Bounds& bounds, const RenderCommand& cmd) {
  if (!cmd.camera_bounds.empty())
    camera = camera_from_bounds(bounds, parse_six("--camera-bounds", cmd.camera_bounds), camera.vfov_degrees);
  if (cmd.fov > 0) camera.vfov_degrees = cmd.fov;
  return camera;
}

void report_scene_warnings(const PreparedScene& prepared, const std::filesystem::path& path) {
  // the loaders name the file in most of their warnings already
  for (const auto& w : prepared.scene.warnings)
    fmt::print(stderr, "warning: {}{}\n", w.starts_with(path.string()) ? "" : path.string() + ": ", w);
  if (prepared.tree.stats.dropped_triangles)
    fmt::print(stderr, "warning: {}: dropped {} degenerate or non-finite triangles\n", path.string(),
               prepared.tree.stats.dropped_triangles);
}

PreparedRender prepare_render(RenderPlan plan, int local_rank, bool reports) {
  OpenedDevices opened = open_render_devices(plan, local_rank);
  const std::filesystem::path& path = plan.command.scene;
  PreparedScene prepared =
      build_render_trees(plan, opened.devices, [&](const TreeChoice& choice) { return prepare_scene(path, choice); });
  apply_render_options(prepared, plan);
  if (reports) report_scene_warnings(prepared, path);
  ProgramCache cache(plan.command.no_cache ? std::nullopt : std::optional(ProgramCache::default_directory()));
  return {.plan = std::move(plan),
          .devices = std::move(opened.devices),
          .pool = std::move(opened.pool),
          .scene = std::move(prepared),
          .cache = std::move(cache)};
}

}  // namespace cohort
