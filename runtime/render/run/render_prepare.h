// Before a render's passes: the devices an input names, opened in a pool, and the scene as the
// input renders it (its tree, white sky, environment map and camera).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/program_cache.h"
#include "runtime/render/run/multi_device.h"
#include "runtime/render/run/render_input.h"
#include "runtime/render/scene/prepared_scene.h"

namespace cohort {

// Devices open in a pool: several renders (of one scene or of several) share them.
struct OpenedDevices {
  std::vector<DeviceInfo> devices;
  std::shared_ptr<DevicePool> pool;
};

// The devices `input` names (device, backend, memory_limit), open; `local_rank` picks among them
// under MPI (select_devices).
OpenedDevices open_render_devices(const RenderInput& input, int local_rank);

// One device, as open_device chooses it from `spec` (the default device, an index or a name
// substring; its support checked), open in a pool: what `cohort bench` measures on.
OpenedDevices open_one_device(Backend backend, const std::string& spec);

// The scene as this process renders it and the devices that render it.
struct PreparedRender {
  RenderInput input;  // settings as the scene set them (white sky)
  std::vector<DeviceInfo> devices;
  std::shared_ptr<DevicePool> pool;  // `devices`, open; several renders share it
  PreparedScene scene;
  ProgramCache cache;
  std::size_t pixels() const { return input.pixels(); }
};

// Loads the scene and builds its trees for the devices opened already (apply_render_options).
// The scene's load warnings are left in scene.scene.warnings for the caller to report.
PreparedRender prepare_render(RenderInput input, OpenedDevices devices);
// The same after opening the devices (open_render_devices).
PreparedRender prepare_render(RenderInput input, int local_rank);

// The scene's trees as the input asks for them (tree, tree_budget_mib, memory_limit, the method):
// `build` makes a PreparedScene with a tree choice (prepare_scene from the file, or from a scene
// loaded already).
PreparedScene build_render_trees(const RenderInput& input, const std::vector<DeviceInfo>& devices,
                                 const std::function<PreparedScene(const TreeChoice&)>& build);

// What the input changes on a built scene: the environment map, the white sky (which also sets
// the input's settings), then the camera (render_camera).
void apply_render_options(PreparedScene& scene, RenderInput& input);
// The same without the camera (a scene several cameras render).
void apply_scene_options(PreparedScene& scene, RenderInput& input);
// The camera camera_bounds and fov make of `camera`.
SceneCamera render_camera(SceneCamera camera, const Bounds& bounds, const RenderInput& input);

}  // namespace cohort
