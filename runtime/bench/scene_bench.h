// `cohort bench` for one scene: the protocol's traversal workloads and white-sky path tracing per
// method, from each requested view (docs/bench-protocol.md, docs/decisions.md "Figures").
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runtime/accel/bvh4.h"
#include "runtime/accel/bvh8.h"
#include "runtime/accel/bvh8f.h"
#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/bench/figures.h"
#include "runtime/backend/device.h"
#include "runtime/render/render_settings.h"
#include "runtime/render/renderer.h"
#include "runtime/render/run/render_prepare.h"
#include "runtime/scene/scene.h"

namespace cohort {

struct BenchView {
  std::string name = "exterior";                    // "exterior": the protocol camera
  std::optional<std::array<float, 6>> camera_bounds;  // eye and target as fractions of the bounds
  float fov = 0;                                     // vertical degrees; 0: the protocol's 45
};

// The protocol's interior view of Crytek Sponza.
BenchView interior_view();

// The view's camera: the protocol camera of the bounds, or the view's fractions of them.
SceneCamera view_camera(const Bounds& bounds, const BenchView& view);

struct BenchOptions {
  std::uint32_t trace_res = 1024;  // protocol rays: trace_res x trace_res primary rays
  std::uint32_t res = 512;         // path tracing image size (square)
  std::uint32_t spp = 4;
  unsigned reps = 3;
  bool traversal = true;              // the primary and diffuse workloads
  std::vector<std::string> methods;   // white-sky path tracing; empty: none
  SortSettings sort;                  // hash/pth, as render's
  std::string tree = "auto";          // tree_options: the device's tree unless deep or compact
};

struct MethodFigures {
  std::string method;
  RateFigure rays_per_second;     // path-tracing rays/s: every ray over the render loop's wall time
  RateFigure samples_per_second;  // res * res * spp over the same time
  // res * res * spp over the process's CPU seconds (every thread) of the render's run (the run of
  // `cohort render`, render_run.h; the scene uploaded before it): on a CPU device, a figure that
  // other programs on a loaded machine disturb far less than wall time
  RateFigure samples_per_cpu_second;
  // the repetition with the median rate, its figures whole (its image dropped): rays, kernel
  // seconds, SIMD efficiency, the wavefront pool, the sort, auto's pick, the render's seconds
  RenderResult median;
  std::map<std::string, double> breakdown;  // device seconds per stage of it (time_breakdown)
  // device time per pass over every repetition (stragglers: a max far above the median), and the
  // most KD-tree nodes one ray visited
  double pass_seconds_median = 0, pass_seconds_max = 0;
  std::uint32_t max_nodes_per_ray = 0;
};

struct ViewFigures {
  BenchView view;
  SceneCamera camera;
  std::optional<TraceFigures> primary, diffuse;
  std::vector<MethodFigures> methods;
};

struct SceneFigures {
  std::filesystem::path path;
  std::size_t triangles = 0;
  double load_seconds = 0;
  KdTreeStats kdtree;
  std::string tree_kind;             // PreparedScene::tree_kind(): deep, compact or bvh4
  double build_seconds = 0;          // PreparedScene::build_seconds(): the tree, or the BVH and its one leaf
  std::optional<Bvh4Stats> bvh4;     // with --tree bvh4 (the KD-tree is then one leaf)
  std::optional<Bvh8Stats> bvh8;     // with --tree bvh8 (likewise)
  std::optional<Bvh8fStats> bvh8f;   // with --tree bvh8f (likewise)
  Bounds bounds;
  std::vector<ViewFigures> views;
};

// Device seconds per kernel name grouped into the stages of a method: "pth walk" (or "hash codes"),
// "sort", "resume traversal" (which reads the rays in sorted order, the reorder), "traversal",
// "shadow rays", "shading", "megakernel" (naive) and "other" (generate, finish, accumulate, counters).
std::map<std::string, double> time_breakdown(const std::map<std::string, double>& kernel_seconds);

// The device a bench measures on, as its JSON names it.
struct BenchDevice {
  DeviceInfo info;
  Backend backend = Backend::opencl;
  std::string compile_options;  // the kernels' build options there
};
BenchDevice bench_device(DevicePool& pool);  // of the pool's first device

// Loads and builds the scene, then measures every view on `devices` (`cohort bench` opens one:
// open_one_device): the traversal workloads on the first device's thread, the path tracing through
// a render's run (render_run.h), the run `cohort render` takes. `log` receives one line per figure as it is measured (progress on a
// slow device); may be empty.
SceneFigures bench_scene(const OpenedDevices& devices, const std::filesystem::path& path,
                         const std::vector<BenchView>& views, const BenchOptions& options,
                         const std::function<void(const std::string&)>& log = {});

}  // namespace cohort
