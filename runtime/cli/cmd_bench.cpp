// `cohort bench`: the protocol's traversal workloads and white-sky path tracing per method, as a
// readable table and a JSON file (docs/bench-protocol.md, docs/decisions.md "Figures").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "runtime/bench/bench_json.h"
#include "runtime/bench/gate_bench.h"
#include "runtime/bench/mesh_export.h"
#include "runtime/bench/scene_bench.h"
#include "runtime/backend/open_device.h"
#include "runtime/cli/commands.h"
#include "runtime/cli/parse_values.h"
#include "runtime/render/methods/methods.h"
#include "runtime/scene/scene.h"
#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    if (comma > start) parts.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  return parts;
}

std::vector<std::string> bench_methods(const std::string& list) {
  if (list == "none") return {};
  if (list.empty() || list == "all") return method_names();
  std::vector<std::string> names = split(list);
  for (const auto& n : names) find_method(n);  // InputError for an unknown name
  return names;
}

std::vector<BenchView> bench_views(const BenchCommand& cmd) {
  std::vector<BenchView> views;
  for (const std::string& v : split(cmd.views)) {
    if (v == "exterior") views.push_back(BenchView{});
    else if (v == "interior") views.push_back(interior_view());
    else throw InputError(fmt::format("--view: unknown view '{}' (exterior, interior)", v));
  }
  if (!cmd.camera_bounds.empty() || cmd.fov > 0) {
    BenchView custom{"custom", std::nullopt, cmd.fov};
    if (!cmd.camera_bounds.empty()) custom.camera_bounds = parse_six("--camera-bounds", cmd.camera_bounds);
    views.push_back(custom);
  }
  if (views.empty()) throw InputError("--view: no view to measure");
  return views;
}

std::string mrays(const RateFigure& f) { return fmt::format("{:.2f} ({:.2f})", f.median() * 1e-6, f.best() * 1e-6); }

void print_view(const SceneFigures& s, const ViewFigures& v) {
  fmt::print("\n{} [{} view], {} triangles, {} tree build {:.3f}s\n", s.path.string(), v.view.name, s.triangles,
             s.tree_kind, s.build_seconds);
  if (v.primary && v.diffuse)
    fmt::print("  traversal Mrays/s, median (best): primary {} with {} hits of {} rays; diffuse {} over {} rays\n",
               mrays(v.primary->rays_per_second), v.primary->hits, v.primary->rays, mrays(v.diffuse->rays_per_second),
               v.diffuse->rays);
  if (v.methods.empty()) return;
  fmt::print("  | method | path-tracing Mrays/s (best) | M samples/s | SIMD eff. | stages (ms): walk / sort / resume / "
             "traversal / shadow / shading / other |\n");
  for (const MethodFigures& m : v.methods) {
    const auto stage = [&](const char* a, const char* b = nullptr) {
      double t = 0;
      for (const char* k : {a, b})
        if (k && m.breakdown.count(k)) t += m.breakdown.at(k);
      return t * 1e3;
    };
    fmt::print("  | {} | {} | {:.3f} | {:.3f} | {:.1f} / {:.1f} / {:.1f} / {:.1f} / {:.1f} / {:.1f} / {:.1f} |\n",
               m.method, mrays(m.rays_per_second), m.samples_per_second.median() * 1e-6, m.median.simd_efficiency,
               stage("pth walk", "hash codes"), stage("sort"), stage("resume traversal"),
               stage("traversal", "megakernel"), stage("shadow rays"), stage("shading"), stage("other"));
  }
  const auto find = [&](const std::string& name) {
    auto it = std::find_if(v.methods.begin(), v.methods.end(), [&](const auto& m) { return m.method == name; });
    return it == v.methods.end() ? nullptr : &*it;
  };
  if (const MethodFigures* pth = find("pth")) {
    const MethodFigures* best = nullptr;
    for (const char* name : {"naive", "sc", "rg", "sc+rg", "hash"})
      if (const MethodFigures* m = find(name))
        if (!best || m->rays_per_second.median() > best->rays_per_second.median()) best = m;
    if (const MethodFigures* naive = find("naive"))
      fmt::print("  pth / naive: {:.2f}x\n", pth->rays_per_second.median() / naive->rays_per_second.median());
    if (best)
      fmt::print("  pth / best of naive, sc, rg, sc+rg, hash ({}): {:.2f}x\n", best->method,
                 pth->rays_per_second.median() / best->rays_per_second.median());
  }
  if (const MethodFigures* automatic = find("auto")) {
    const MethodFigures* winner = nullptr;
    for (const MethodFigures& m : v.methods)
      if (m.method != "auto" && (!winner || m.rays_per_second.median() > winner->rays_per_second.median())) winner = &m;
    if (winner)
      fmt::print("  auto picked {} (probe included: {:.2f}x the fastest method by name, {})\n", automatic->median.auto_choice.method,
                 automatic->rays_per_second.median() / winner->rays_per_second.median(), winner->method);
  }
}

// --gate: every order's trace rate against generation order, and what its sort costs.
int run_gate(const BenchCommand& cmd, const std::vector<BenchView>& views, DevicePool& pool, const DeviceInfo& info) {
  const ProgramCache cache(ProgramCache::default_directory());
  GateOptions options;
  options.res = parse_resolution(cmd.trace_resolution + "x" + cmd.trace_resolution).first;
  options.bounces = cmd.bounces;
  options.reps = cmd.reps;
  nlohmann::json all = nlohmann::json::array();
  // the tree the renderer traces (--tree auto: the 4-wide BVH, as for pth), or a KD-tree; the PTH
  // keys walk its top
  const TreeChoice tree = tree_options(cmd.tree, info, false, true);
  for (const auto& path : cmd.scenes) {
    PreparedScene prepared = prepare_scene(path, tree);
    for (const BenchView& view : views) {
      const SceneCamera camera = view_camera(prepared.scene.bounds(), view);
      std::vector<GateBounce> bounces;
      pool.run_on(0, [&](const Device& device) { bounces = gate_bench(device, cache, prepared, camera, options); });
      fmt::print("\n{} [{} view], {} triangles, {}, {}x{} primary rays: trace Mrays/s median (best), x generation "
                 "order, device sort ms\n",
                 path.string(), view.name, prepared.scene.triangle_count(), prepared.tree_kind(), options.res,
                 options.res);
      for (const GateBounce& b : bounces) {
        const double base = b.orders.front().rays_per_second.median();
        const double base_ms = b.rays / base * 1e3;
        fmt::print("  bounce {}: {} rays, trace {:.2f} ms in generation order{}\n", b.bounce, b.rays, base_ms,
                   b.hits_agree ? "" : " (HITS DIFFER BETWEEN ORDERS)");
        nlohmann::json orders = nlohmann::json::object();
        for (const GateOrder& o : b.orders) {
          const double ms = b.rays / o.rays_per_second.median() * 1e3;
          fmt::print("    {:18} {:>8.2f} ({:.2f})  {:.3f}x  sort {:.3f} ms ({} bits)  net {:.3f}x\n", o.name,
                     o.rays_per_second.median() * 1e-6, o.rays_per_second.best() * 1e-6,
                     o.rays_per_second.median() / base, o.sort_ms, o.key_bits, base_ms / (ms + o.sort_ms));
          orders[o.name] = {{"mrays_per_second", rate_json(o.rays_per_second)}, {"key_bits", o.key_bits},
                            {"sort_ms", o.sort_ms}, {"speedup", o.rays_per_second.median() / base},
                            {"net_speedup", base_ms / (ms + o.sort_ms)}};
        }
        all.push_back({{"scene", path.string()}, {"view", view.name}, {"tree", prepared.tree_kind()},
                       {"res", options.res}, {"bounce", b.bounce},
                       {"rays", b.rays}, {"hits_agree", b.hits_agree}, {"orders", orders}});
      }
    }
  }
  fmt::print("\nnet: trace time in generation order over (trace time in this order + its sort); the payload gather "
             "is not counted\n");
  if (!cmd.json.empty()) {
    write_file_atomically(cmd.json, nlohmann::json{{"device", info.name}, {"driver", info.driver_version},
                                                   {"gate", all}}.dump(2) + "\n");
    fmt::print("wrote {}\n", cmd.json);
  }
  return 0;
}

}  // namespace

int run_bench(const BenchCommand& cmd) {
  BenchOptions options;
  options.res = parse_resolution(cmd.resolution + "x" + cmd.resolution).first;
  options.trace_res = parse_resolution(cmd.trace_resolution + "x" + cmd.trace_resolution).first;
  options.spp = cmd.spp;
  options.reps = cmd.reps;
  options.traversal = !cmd.no_traversal;
  options.methods = bench_methods(cmd.methods);
  options.sort = cmd.sort;
  options.tree = cmd.tree;
  const std::vector<BenchView> views = bench_views(cmd);
  // one device, in a pool: the renders take the run of `cohort render`, everything on the device's thread
  const OpenedDevices opened = open_one_device(parse_backend(cmd.backend), cmd.device);
  const BenchDevice device = bench_device(*opened.pool);
  const DeviceInfo& info = device.info;
  fmt::print("device: {} ({}, driver {}), {} compute units\n", info.name, info.platform_name, info.driver_version,
             info.compute_units);
  if (cmd.gate) return run_gate(cmd, views, *opened.pool, info);
  std::vector<SceneFigures> scenes;
  for (const auto& path : cmd.scenes) {
    scenes.push_back(bench_scene(opened, path, views, options, [](const std::string& line) {
      fmt::print(stderr, "{}\n", line);
    }));
    for (const auto& v : scenes.back().views) print_view(scenes.back(), v);
  }
  fmt::print("\nwhite sky at {0}x{0}, {1} spp; protocol rays at {2}x{2}; median of {3} (best)\n", options.res,
             options.spp, options.trace_res, options.reps);
  if (!cmd.json.empty()) {
    write_file_atomically(cmd.json, bench_json(device, options, scenes).dump(2) + "\n");
    fmt::print("wrote {}\n", cmd.json);
  }
  return 0;
}

int run_export(const ExportCommand& cmd) {
  const Scene scene = load_scene(cmd.scene);
  auto positions = midpoint_subdivide(scene.positions, cmd.subdivide);
  if (cmd.copies > 1) positions = copies_along_z(positions, cmd.copies);
  write_ply(cmd.output, positions);
  fmt::print("wrote {}: {} triangles\n", cmd.output.string(), positions.size() / 3);
  return 0;
}

}  // namespace cohort
