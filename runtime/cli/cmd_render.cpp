#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "runtime/backend/open_device.h"
#include "runtime/cli/commands.h"
#include "runtime/cli/output_paths.h"
#include "runtime/cli/parse_values.h"
#include "runtime/cli/progress.h"
#include "runtime/render/environment_map.h"
#include "runtime/render/prepared_scene.h"
#include "runtime/render/methods.h"
#include "runtime/render/renderer.h"
#include "runtime/render/workloads.h"
#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"
#include "runtime/util/hash.h"
#include "runtime/cli/interrupt.h"
#include "runtime/render/checkpoint.h"

namespace cohort {
namespace {

nlohmann::json stats_json(const RenderCommand& cmd, const DeviceInfo& device, const PreparedScene& prepared,
                          const RenderResult& r, const OutputPaths& out) {
  nlohmann::json j;
  j["scene"] = cmd.scene.string();
  j["method"] = cmd.settings.method;
  j["device"] = {{"backend", cmd.backend}, {"name", device.name}, {"platform", device.platform_name}, {"driver", device.driver_version},
                 {"compute_units", device.compute_units}};
  j["image"] = {{"width", cmd.settings.width}, {"height", cmd.settings.height}, {"spp", r.samples},
                {"exr", out.exr.string()}, {"png", out.png.string()}};
  j["settings"] = {{"max_depth", cmd.settings.max_depth}, {"rr_depth", cmd.settings.rr_depth},
                   {"seed", cmd.settings.seed}, {"nee", cmd.settings.nee}, {"mis", cmd.settings.mis},
                   {"russian_roulette", cmd.settings.russian_roulette}};
  const auto& ts = prepared.tree.stats;
  j["scene_stats"] = {{"triangles", prepared.scene.triangle_count()}, {"dropped_triangles", ts.dropped_triangles},
                      {"emitters", prepared.tables.emitters.entries.size()},
                      {"punctual_lights", prepared.tables.punctual.lights.size()}};
  if (prepared.tables.environment) j["scene_stats"]["environment_map"] = prepared.tables.environment->source.string();
  j["kdtree"] = {{"depth", ts.depth}, {"nodes", ts.node_count}, {"leaves", ts.leaf_count},
                 {"average_leaf_triangles", ts.average_leaf_triangles}, {"sah_cost", ts.sah_cost},
                 {"bytes", ts.bytes}};
  j["timings"] = {{"load_seconds", prepared.load_seconds}, {"build_seconds", ts.build_seconds},
                  {"compile_seconds", r.compile_seconds}, {"compile_from_cache", r.compile_from_cache},
                  {"render_seconds", r.render_seconds}};
  j["rays"] = r.rays;
  j["rays_per_second"] = r.render_seconds > 0 ? static_cast<double>(r.rays) / r.render_seconds : 0.0;
  j["samples_per_second"] =
      r.render_seconds > 0 ? double(r.samples) * cmd.settings.width * cmd.settings.height / r.render_seconds : 0.0;
  j["dropped_samples"] = r.dropped_samples;
  nlohmann::json kernels;
  for (const auto& [name, seconds] : r.kernel_seconds)
    kernels[name] = {{"seconds", seconds}, {"rays_per_second", seconds > 0 ? double(r.rays) / seconds : 0.0}};
  j["kernels"] = kernels;
  if (r.wavefront_size) {
    j["wavefront"] = {{"slots", r.wavefront_size}, {"bytes_per_path", r.path_state_bytes},
                      {"simd_efficiency", r.simd_efficiency}};
    if (!r.code_layout.empty())
      j["coherence"] = {{"code", r.code_layout}, {"pth_levels", r.pth_levels}, {"subtree_nodes", r.pth_subtree_nodes},
                        {"speculative", r.speculative}};
    nlohmann::json bounces = nlohmann::json::array();
    for (const auto& it : r.iterations)
      bounces.push_back({{"live_paths", it.live_paths}, {"extension_rays", it.live_paths},
                         {"shadow_rays", it.shadow_rays},
                         {"simd_efficiency", it.simd_groups ? it.simd_efficiency_sum / double(it.simd_groups) : 0.0},
                         {"kernel_seconds", it.kernel_seconds}});
    j["bounces"] = bounces;
  }
  return j;
}

// What decides the image: a checkpoint may only be resumed by a render that would produce it.
std::uint64_t render_fingerprint(const RenderCommand& cmd, const PreparedScene& p) {
  const auto& s = cmd.settings;
  const auto& c = p.camera;
  const std::string text = fmt::format(
      "{}|{}x{}|seed {}|depth {} rr {}|nee {} mis {} rr {}|env {}|eye {} {} {}|target {} {} {}|fov {}|tris {}",
      std::filesystem::weakly_canonical(cmd.scene).string(), s.width, s.height, s.seed, s.max_depth, s.rr_depth, s.nee,
      s.mis, s.russian_roulette, s.environment ? fmt::format("{} {} {}", s.environment->x, s.environment->y,
                                                               s.environment->z)
                                               : "none",
      c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.vfov_degrees, p.tree.triangles.size());
  // an environment map is named by its file (older checkpoints, without one, keep their fingerprint)
  if (p.tables.environment)
    return fnv1a64(text + "|envmap " + std::filesystem::weakly_canonical(p.tables.environment->source).string());
  return fnv1a64(text);
}

}  // namespace

int run_render(const RenderCommand& cmd_in) {
  RenderCommand cmd = cmd_in;
  std::tie(cmd.settings.width, cmd.settings.height) = parse_resolution(cmd.resolution);
  const bool env_map = is_environment_map_path(cmd.environment);
  if (!cmd.environment.empty() && !env_map) cmd.settings.environment = parse_rgb("--env", cmd.environment);
  if (cmd.settings.spp == 0 && cmd.settings.time_limit <= 0)
    throw InputError("--spp 0 needs --time SECONDS to say when to stop");
  // check where the outputs go before spending time on the render
  const OutputPaths out = output_paths(cmd.output, cmd.scene);

  const auto memory_limit =
      cmd.memory_limit_mib > 0 ? static_cast<std::uint64_t>(cmd.memory_limit_mib * 1048576.0) : std::uint64_t(0);
  const std::unique_ptr<Device> opened = open_device(parse_backend(cmd.backend), cmd.device, memory_limit);
  const Device& cl = *opened;
  const DeviceInfo& device = cl.info();
  PreparedScene prepared = prepare_scene(cmd.scene);
  if (env_map) set_environment_map(prepared.tables, load_environment_map(cmd.environment));
  if (cmd.white_sky) apply_white_sky(prepared, cmd.settings);
  if (!cmd.camera_bounds.empty())
    prepared.camera = camera_from_bounds(prepared.scene.bounds(), parse_six("--camera-bounds", cmd.camera_bounds),
                                         prepared.camera.vfov_degrees);
  if (cmd.fov > 0) prepared.camera.vfov_degrees = cmd.fov;
  for (const auto& w : prepared.scene.warnings) fmt::print(stderr, "warning: {}: {}\n", cmd.scene.string(), w);
  if (prepared.tree.stats.dropped_triangles)
    fmt::print(stderr, "warning: {}: dropped {} degenerate or non-finite triangles\n", cmd.scene.string(),
               prepared.tree.stats.dropped_triangles);

  const ProgramCache cache(cmd.no_cache ? std::nullopt : std::optional(ProgramCache::default_directory()));
  const DeviceScene device_scene = upload_scene(cl, prepared.tree, prepared.tables);
  const std::uint64_t fingerprint = render_fingerprint(cmd, prepared);
  RenderControl control;
  if (cmd.resume) control.resume_from = load_checkpoint(out.checkpoint, fingerprint);
  if (control.resume_from) fmt::print("resuming {} at {} spp\n", out.checkpoint.string(), control.resume_from->samples);
  if (cmd.checkpoint || cmd.resume) {
    control.checkpoint_seconds = cmd.checkpoint_seconds;
    control.checkpoint = [&](const FilmState& film) { save_checkpoint(out.checkpoint, fingerprint, film); };
  }
  const InterruptGuard interrupt;
  control.stop_requested = [&] { return interrupt.requested(); };
  ProgressReporter reporter(stderr);
  const RenderResult result = render(cl, cache, device_scene, prepared.camera, cmd.settings,
                                     [&](const Progress& p) { reporter.update(p); }, control);
  reporter.finish();

  write_exr(out.exr, result.image);
  write_png(out.png, result.image);
  const double mrays = result.render_seconds > 0 ? double(result.rays) / result.render_seconds * 1e-6 : 0;
  if (cmd.verbose) {
    const auto& ts = prepared.tree.stats;
    fmt::print("device: {} ({})\n", device.name, device.platform_name);
    fmt::print("scene: {} triangles, {} emissive, {} punctual lights, loaded in {:.3f}s\n",
               prepared.scene.triangle_count(), prepared.tables.emitters.entries.size(),
               prepared.tables.punctual.lights.size(), prepared.load_seconds);
    if (prepared.tables.environment)
      fmt::print("environment map: {}, {}x{}\n", prepared.tables.environment->source.string(),
                 prepared.tables.environment->width, prepared.tables.environment->height);
    fmt::print("kd-tree: depth {}, {} nodes, {} leaves, {:.2f} triangles per leaf, SAH cost {:.2f}, built in {:.3f}s\n",
               ts.depth, ts.node_count, ts.leaf_count, ts.average_leaf_triangles, ts.sah_cost, ts.build_seconds);
    fmt::print("kernel compile: {:.3f}s ({})\n", result.compile_seconds, result.compile_from_cache ? "warm, from cache" : "cold");
    const auto features = device_scene.features.names();
    fmt::print("kernel features: {}\n", features.empty() ? std::string("none (Lambertian only)")
                                                         : fmt::format("{}", fmt::join(features, " ")));
    for (const auto& [name, seconds] : result.kernel_seconds) fmt::print("kernel {}: {:.3f}s\n", name, seconds);
    if (result.wavefront_size)
      fmt::print("wavefront: {} path slots x {} bytes = {:.1f} MiB, {} bounces, SIMD efficiency {:.3f}\n",
                 result.wavefront_size, result.path_state_bytes,
                 result.wavefront_size * result.path_state_bytes / 1048576.0, result.iterations.size(),
                 result.simd_efficiency);
    if (!result.code_layout.empty())
      fmt::print("coherence code: {}; PTH subtree {} levels, {} nodes\n", result.code_layout, result.pth_levels,
                 result.pth_subtree_nodes);
  }
  if (result.dropped_samples)
    fmt::print(stderr, "warning: {} NaN or infinite samples were dropped\n", result.dropped_samples);
  fmt::print("rendered {}x{} at {} spp in {:.2f}s ({:.2f} Mrays/s)\n", cmd.settings.width, cmd.settings.height,
             result.samples, result.render_seconds, mrays);
  fmt::print("wrote {}\nwrote {}\n", out.exr.string(), out.png.string());
  if (cmd.checkpoint || cmd.resume) fmt::print("wrote {}\n", out.checkpoint.string());
  if (!cmd.stats_file.empty()) {
    write_file_atomically(cmd.stats_file, stats_json(cmd, device, prepared, result, out).dump(2) + "\n");
    fmt::print("wrote {}\n", cmd.stats_file);
  }
  if (result.interrupted) {
    fmt::print(stderr, "interrupted by signal {} at {} spp: the image so far is saved{}\n", interrupt.signal_number(),
               result.samples, cmd.checkpoint || cmd.resume ? "; --resume continues it" : "");
    return 128 + interrupt.signal_number();
  }
  return 0;
}

}  // namespace cohort
