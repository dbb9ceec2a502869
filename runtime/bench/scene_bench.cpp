#include "runtime/bench/scene_bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <ctime>

#include "runtime/backend/device_support.h"
#include "runtime/bench/trace_bench.h"
#include "runtime/render/run/render_run.h"
#include "runtime/render/workloads.h"
#include "runtime/util/median.h"

namespace cohort {

BenchView interior_view() { return BenchView{"interior", std::array<float, 6>{0.25f, 0.2f, 0.5f, 0.75f, 0.35f, 0.5f}, 60.f}; }

SceneCamera view_camera(const Bounds& bounds, const BenchView& view) {
  SceneCamera c = framing_camera(bounds);
  if (view.camera_bounds) c = camera_from_bounds(bounds, *view.camera_bounds, c.vfov_degrees);
  if (view.fov > 0) c.vfov_degrees = view.fov;
  return c;
}

std::map<std::string, double> time_breakdown(const std::map<std::string, double>& kernel_seconds) {
  std::map<std::string, double> stages;
  for (const auto& [name, s] : kernel_seconds) {
    std::string stage = "other";
    if (name == "pth") stage = "pth walk";
    else if (name == "hash") stage = "hash codes";
    else if (name.starts_with("sort")) stage = "sort";
    else if (name == "resume") stage = "resume traversal";
    else if (name == "extend") stage = "traversal";
    else if (name == "shadow") stage = "shadow rays";
    else if (name == "shade") stage = "shading";
    else if (name == "render_naive") stage = "megakernel";
    stages[stage] += s;
  }
  return stages;
}

namespace {

// The render a bench measures: the white sky at res x res with spp samples, the sort and the tree
// as given.
RenderInput bench_input(const std::filesystem::path& path, const BenchOptions& options) {
  RenderInput input{.scene = path};
  input.settings.width = input.settings.height = options.res;
  input.settings.spp = options.spp;
  input.settings.sort = options.sort;
  input.white_sky = true;
  input.tree = options.tree;
  input.runs_sorting_methods = std::any_of(options.methods.begin(), options.methods.end(),
                                           [](const std::string& m) { return m == "hash" || m == "pth"; });
  return input;
}

// Renders `method` `reps` times through the run, with no progress and no checkpoint.
MethodFigures bench_method(PreparedRender& render, const RenderTeam& team, const std::string& method, unsigned reps) {
  render.input.settings.method = method;
  const RenderSettings& settings = render.input.settings;
  MethodFigures f;
  f.method = method;
  std::vector<RenderResult> runs;
  std::vector<double> pass_seconds;
  for (unsigned r = 0; r < std::max(reps, 1u); ++r) {
    const std::clock_t cpu_start = std::clock();
    RenderResult result = run_render_passes(render, team, {}, {}).result;
    const double cpu = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    result.image = Image{};  // keep the figures only
    const double s = result.render_seconds;
    const double samples = double(settings.width) * settings.height * result.samples;
    f.rays_per_second.runs.push_back(s > 0 ? double(result.rays) / s : 0.0);
    f.samples_per_second.runs.push_back(s > 0 ? samples / s : 0.0);
    f.samples_per_cpu_second.runs.push_back(cpu > 0 ? samples / cpu : 0.0);
    pass_seconds.insert(pass_seconds.end(), result.pass_kernel_seconds.begin(), result.pass_kernel_seconds.end());
    f.max_nodes_per_ray = std::max(f.max_nodes_per_ray, result.max_nodes_per_ray);
    runs.push_back(std::move(result));
  }
  // the repetition whose rate is the median (the upper one of an even count) gives the breakdown
  std::vector<std::size_t> order(runs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return f.rays_per_second.runs[a] < f.rays_per_second.runs[b]; });
  f.median = std::move(runs[order[order.size() / 2]]);
  f.breakdown = time_breakdown(f.median.kernel_seconds);
  f.pass_seconds_median = median(pass_seconds);
  if (!pass_seconds.empty()) f.pass_seconds_max = *std::max_element(pass_seconds.begin(), pass_seconds.end());
  return f;
}

}  // namespace

BenchDevice bench_device(DevicePool& pool) {
  BenchDevice out;
  pool.run_on(0, [&](const Device& device) {
    out = {device.info(), device.backend(), device.compile_options()};
  });
  return out;
}

SceneFigures bench_scene(const OpenedDevices& devices, const std::filesystem::path& path,
                         const std::vector<BenchView>& views, const BenchOptions& options,
                         const std::function<void(const std::string&)>& log_line) {
  const auto log = [&](const std::string& s) {
    if (log_line) log_line(s);
  };
  PreparedRender render = prepare_render(bench_input(path, options), devices);
  const PreparedScene& prepared = render.scene;
  DevicePool& pool = *render.pool;

  SceneFigures out;
  out.path = path;
  out.triangles = prepared.scene.triangle_count();
  out.load_seconds = prepared.load_seconds;
  out.kdtree = prepared.tree.stats;
  out.tree_kind = prepared.tree_kind();
  out.build_seconds = prepared.build_seconds();
  if (prepared.bvh4) out.bvh4 = prepared.bvh4->stats;
  if (prepared.bvh8) out.bvh8 = prepared.bvh8->stats;
  if (prepared.bvh8f) out.bvh8f = prepared.bvh8f->stats;
  out.bounds = prepared.scene.bounds();
  log(fmt::format("{}: {} triangles, {} tree built in {:.3f}s", path.string(), out.triangles, out.tree_kind,
                  out.build_seconds));

  // what this scene put on the device goes when the bench leaves it, on the device's thread (a
  // CUDA context is current there), the scene's upload with it: the next scene may take its address
  std::optional<TraceBench> tracer;
  struct Release {
    DevicePool& pool;
    std::optional<TraceBench>& tracer;
    ~Release() {
      try {
        pool.run_on(0, [&](const Device&) { tracer.reset(); });
        pool.drop_scenes();
      } catch (...) {  // unwinding already, or a device that failed: nothing more to free
      }
    }
  } release{pool, tracer};
  bool pixel_tiles = false;
  if (options.traversal)
    pool.run_on(0, [&](const Device& device) {
      tracer.emplace(device, render.cache, prepared.tree, prepared.bvh());
      pixel_tiles = device_support(device.info()).pixel_tiles;
    });
  // uploaded before any clock starts (a render's own upload is not rendering)
  if (!options.methods.empty()) pool.run_on(0, prepared, [](const Device&, const DeviceScene&) {});
  const auto team = solo_render_team();

  for (const BenchView& view : views) {
    ViewFigures vf;
    vf.view = view;
    vf.camera = view_camera(out.bounds, view);
    if (tracer) {
      // in the order the device's renders launch camera rays (rows, or tiles on GPUs)
      const auto order = protocol_pixel_order(options.trace_res, pixel_tiles);
      const auto primary = protocol_primary_rays(vf.camera, options.trace_res, order);
      pool.run_on(0, [&](const Device&) { vf.primary = tracer->trace(primary, options.reps); });
      log(fmt::format("  {} primary: {:.2f} Mrays/s median, {:.2f} best, {} hits", view.name,
                      vf.primary->rays_per_second.median() * 1e-6, vf.primary->rays_per_second.best() * 1e-6,
                      vf.primary->hits));
      const auto diffuse =
          protocol_diffuse_rays(primary, vf.primary->closest, prepared.scene.positions, out.bounds.diagonal(), order);
      vf.primary->closest.clear();
      pool.run_on(0, [&](const Device&) { vf.diffuse = tracer->trace(diffuse, options.reps); });
      vf.diffuse->closest.clear();
      log(fmt::format("  {} diffuse: {:.2f} Mrays/s median, {:.2f} best, {} rays", view.name,
                      vf.diffuse->rays_per_second.median() * 1e-6, vf.diffuse->rays_per_second.best() * 1e-6,
                      vf.diffuse->rays));
    }
    render.scene.camera = vf.camera;
    for (const std::string& method : options.methods) {
      vf.methods.push_back(bench_method(render, *team, method, options.reps));
      const MethodFigures& m = vf.methods.back();
      log(fmt::format("  {} {}: {:.2f} Mrays/s, {:.3f} M samples/s median", view.name, method,
                      m.rays_per_second.median() * 1e-6, m.samples_per_second.median() * 1e-6));
      if (m.pass_seconds_max > 2 * m.pass_seconds_median)
        log(fmt::format("  warning: {} {}: slowest pass {:.2f} ms is {:.1f}x the median {:.2f} ms (stragglers? "
                        "most nodes one ray visited: {})",
                        view.name, method, m.pass_seconds_max * 1e3, m.pass_seconds_max / m.pass_seconds_median,
                        m.pass_seconds_median * 1e3, m.max_nodes_per_ray));
    }
    out.views.push_back(std::move(vf));
  }
  return out;
}

}  // namespace cohort
