#include "runtime/render/run/render_prepare.h"

#include <algorithm>

#include "runtime/backend/device_choice.h"
#include "runtime/backend/open_device.h"
#include "runtime/render/scene/environment_map.h"
#include "runtime/render/scene/scene_memory.h"
#include "runtime/render/workloads.h"

namespace cohort {

OpenedDevices open_render_devices(const RenderInput& input, int local_rank) {
  const std::uint64_t limit = input.memory_limit;
  if (input.backend == Backend::opencl) {
    std::vector<DeviceInfo> devices = select_devices(list_backend_devices(Backend::opencl), input.device, local_rank);
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
  const Backend backend = input.backend;
  std::vector<DeviceInfo> devices{open_device(backend, input.device, limit)->info()};
  auto pool = std::make_shared<DevicePool>(
      devices, [backend, spec = input.device, limit](std::size_t) { return open_device(backend, spec, limit); });
  return {std::move(devices), std::move(pool)};
}

OpenedDevices open_one_device(Backend backend, const std::string& spec) {
  // opened on the pool's thread only (a CUDA context is current there); its info comes from there
  auto pool = std::make_shared<DevicePool>(1, [backend, spec](std::size_t) { return open_device(backend, spec); });
  return {pool->infos(), std::move(pool)};
}

PreparedScene build_render_trees(const RenderInput& input, const std::vector<DeviceInfo>& devices,
                                 const std::function<PreparedScene(const TreeChoice&)>& build) {
  // what rays are traced through (tree_options: the BVH unless a tree budget or speculative traversal
  // asks for the KD-tree, which then fits the devices; on CPUs the 8-wide one unless hash or pth
  // runs); any gives the same image
  const TreeChoice tree = tree_options(input.tree, devices, input.needs_kdtree(), input.sorts());
  PreparedScene prepared = build(tree);
  // a BVH has no depth to trade for bytes: where auto's does not fit, it falls back to the KD-tree,
  // trimmed below to fit (no other BVH would: the 8-wide one with blocks of four triangles, the CPU's,
  // is the smallest, about 0.8x the 4-wide one's bytes, and a GPU walks the KD-tree faster than it)
  if (input.memory_limit && input.tree == "auto" && tree.bvh() &&
      scene_memory(prepared.tree, prepared.tables, prepared.bvh()).total() > input.memory_limit)
    prepared = build(TreeChoice{tree.kd});
  if (input.tree_budget_mib > 0)
    prepared.tree = build_kdtree_within(prepared.scene.positions, tree.kd,
                                        static_cast<std::size_t>(input.tree_budget_mib * 1048576.0));
  if (input.memory_limit) fit_scene_to(prepared, input.memory_limit, tree.kd);
  return prepared;
}

void apply_scene_options(PreparedScene& prepared, RenderInput& input) {
  if (!input.environment_map.empty())
    set_environment_map(prepared.tables, load_environment_map(input.environment_map));
  if (input.white_sky) apply_white_sky(prepared, input.settings);
}

void apply_render_options(PreparedScene& prepared, RenderInput& input) {
  apply_scene_options(prepared, input);
  prepared.camera = render_camera(prepared.camera, prepared.scene.bounds(), input);
}

SceneCamera render_camera(SceneCamera camera, const Bounds& bounds, const RenderInput& input) {
  if (input.camera_bounds) camera = camera_from_bounds(bounds, *input.camera_bounds, camera.vfov_degrees);
  if (input.fov > 0) camera.vfov_degrees = input.fov;
  return camera;
}

PreparedRender prepare_render(RenderInput input, OpenedDevices opened) {
  const std::filesystem::path path = input.scene;
  PreparedScene prepared =
      build_render_trees(input, opened.devices, [&](const TreeChoice& choice) { return prepare_scene(path, choice); });
  apply_render_options(prepared, input);
  ProgramCache cache(input.program_cache ? std::optional(ProgramCache::default_directory()) : std::nullopt);
  return {.input = std::move(input),
          .devices = std::move(opened.devices),
          .pool = std::move(opened.pool),
          .scene = std::move(prepared),
          .cache = std::move(cache)};
}

PreparedRender prepare_render(RenderInput input, int local_rank) {
  OpenedDevices opened = open_render_devices(input, local_rank);
  return prepare_render(std::move(input), std::move(opened));
}

}  // namespace cohort
