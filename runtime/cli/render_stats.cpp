#include <fmt/format.h>

#include <algorithm>

#include "runtime/bench/bench_json.h"
#include "runtime/cli/render_steps.h"
#include "runtime/render/run/adaptive.h"
#include "runtime/render/scene/scene_memory.h"
#include "runtime/util/median.h"

namespace cohort {

namespace {

// Median and max of a per-pass count.
nlohmann::json per_pass(const std::vector<std::uint32_t>& counts) {
  const std::vector<double> values(counts.begin(), counts.end());
  return {{"median", median(values)}, {"max", counts.empty() ? 0u : *std::max_element(counts.begin(), counts.end())}};
}

}  // namespace

nlohmann::json stats_json(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths* out,
                          const DenoiseOutcome* denoise) {
  const RenderInput& in = render.input;
  const RenderSettings& settings = in.settings;
  const PreparedScene& prepared = render.scene;
  const RenderResult& r = outcome.result;
  const auto& mean = outcome.image_mean;
  nlohmann::json j;
  j["image_mean"] = {{"rgb", mean.mean}, {"standard_error", mean.standard_error}};
  j["scene"] = in.scene.string();
  j["method"] = settings.method;
  if (!r.auto_choice.method.empty())
    j["auto"] = {{"method", r.auto_choice.method},
                 {"reason", r.auto_choice.reason},
                 {"screen_rows", r.auto_choice.screen_rows},
                 {"probe_seconds", r.auto_choice.probe_seconds},
                 {"probe_rays_per_second", r.auto_choice.probe_rays_per_second},
                 {"final_rays_per_second", r.auto_choice.final_rays_per_second}};
  nlohmann::json devices = nlohmann::json::array();
  for (const RankFigures& rank : outcome.ranks)
    for (const DeviceFigures& d : rank.devices) {
      devices.push_back(d);
      devices.back()["rank"] = rank.rank;
    }
  j["backend"] = backend_name(in.backend);
  j["device"] = devices.at(0);  // the first device, as before several devices
  j["devices"] = devices;
  j["ranks"] = outcome.ranks;
  j["passes"] = r.passes;
  // stragglers show as passes far slower than the median, and as rays that visit much of the tree
  std::vector<double> pass_seconds;
  std::uint32_t max_nodes = 0;
  for (const RankFigures& rank : outcome.ranks)
    for (const DeviceFigures& d : rank.devices) {
      pass_seconds.insert(pass_seconds.end(), d.pass_kernel_seconds.begin(), d.pass_kernel_seconds.end());
      max_nodes = std::max(max_nodes, d.max_nodes_per_ray);
    }
  j["pass_seconds"] = {{"median", median(pass_seconds)},
                       {"max", pass_seconds.empty() ? 0.0 : *std::max_element(pass_seconds.begin(), pass_seconds.end())}};
  j["max_nodes_per_ray"] = max_nodes;
  if (settings.straggler_rays) {
    nlohmann::json per_pass = nlohmann::json::array(), worst = nlohmann::json::array();
    for (const auto& p : r.pass_stragglers) per_pass.push_back({{"max", p.max}, {"p9999", p.p9999}});
    // hex floats: the exact bits, so the ray replays as traced
    const auto hex = [](const glm::vec3& v) {
      return nlohmann::json::array({fmt::format("{:a}", v.x), fmt::format("{:a}", v.y), fmt::format("{:a}", v.z)});
    };
    for (const auto& w : r.worst_rays)
      worst.push_back({{"nodes", w.nodes}, {"org", hex(w.org)}, {"dir", hex(w.dir)},
                       {"tmin", fmt::format("{:a}", w.tmin)}, {"tmax", fmt::format("{:a}", w.tmax)}});
    j["stragglers"] = {{"rays", "extension rays of this device (rank 0's devices under MPI)"},
                       {"per_pass", per_pass}, {"worst", worst}};
  }
  j["image"] = {{"width", settings.width}, {"height", settings.height}, {"spp", r.samples}};
  if (out) {
    j["image"]["exr"] = out->exr.string();
    j["image"]["png"] = out->png.string();
  }
  j["settings"] = {{"max_depth", settings.max_depth}, {"rr_depth", settings.rr_depth},
                   {"seed", settings.seed}, {"nee", settings.nee}, {"mis", settings.mis},
                   {"russian_roulette", settings.russian_roulette}};
  const auto& ts = prepared.tree.stats;
  j["scene_stats"] = {{"triangles", prepared.scene.triangle_count()}, {"dropped_triangles", ts.dropped_triangles},
                      {"emitters", prepared.tables.emitters.entries.size()},
                      {"punctual_lights", prepared.tables.punctual.lights.size()}};
  if (prepared.tables.environment) j["scene_stats"]["environment_map"] = prepared.tables.environment->source.string();
  j["kdtree"] = {{"kind", prepared.tree_kind()},
                 {"depth", ts.depth},
                 {"nodes", ts.node_count},
                 {"leaves", ts.leaf_count},
                 {"average_leaf_triangles", ts.average_leaf_triangles},
                 {"sah_cost", ts.sah_cost},
                 {"bytes", ts.bytes}};
  if (const Bvh4Stats* bvh = prepared.bvh_stats()) j["kdtree"][prepared.tree_kind()] = bvh4_json(*bvh);
  const SceneMemory memory = scene_memory(prepared.tree, prepared.tables, prepared.bvh());
  const double kept = static_cast<double>(std::max<std::size_t>(prepared.tree.triangles.size(), 1));
  j["device_memory"] = {{"nodes", memory.nodes}, {"leaf_lists", memory.leaf_lists},
                        {"triangles", memory.triangles}, {"shading", memory.shading},
                        {"total", memory.total()}, {"bytes_per_triangle", static_cast<double>(memory.total()) / kept}};
  j["timings"] = {{"load_seconds", prepared.load_seconds}, {"build_seconds", prepared.build_seconds()},
                  {"compile_seconds", r.compile_seconds}, {"compile_from_cache", r.compile_from_cache},
                  {"render_seconds", r.render_seconds}, {"render_cpu_seconds", r.render_cpu_seconds}};
  j["rays"] = r.rays;
  j["rays_per_second"] = r.render_seconds > 0 ? static_cast<double>(r.rays) / r.render_seconds : 0.0;
  const AdaptiveFigures adaptive = adaptive_figures(outcome.film, settings.target_error);
  j["samples_per_second"] = r.render_seconds > 0 ? double(adaptive.samples) / r.render_seconds : 0.0;
  if (settings.target_error > 0)
    j["adaptive"] = {{"target_error", settings.target_error},
                     {"tile", kAdaptiveTile},
                     {"samples", adaptive.samples},
                     {"mean_spp", double(adaptive.samples) / double(std::max<std::size_t>(render.pixels(), 1))},
                     {"min_pixel_spp", adaptive.min_pixel_samples},
                     {"max_pixel_spp", adaptive.max_pixel_samples},
                     {"tiles", adaptive.tiles},
                     {"tiles_stopped_early", adaptive.tiles_stopped},
                     {"tiles_below_target", adaptive.tiles_converged},
                     {"estimated_error", adaptive.estimated_error}};
  j["dropped_samples"] = r.dropped_samples;
  // the round trips inside a pass (the wavefront loop reads its counters every few bounces), and
  // the device commands of its ray sorts
  j["host_reads_per_pass"] = per_pass(r.pass_host_reads);
  j["sort_launches"] = per_pass(r.pass_sort_launches);
  nlohmann::json kernels;
  for (const auto& [name, seconds] : r.kernel_seconds)
    kernels[name] = {{"seconds", seconds}, {"rays_per_second", seconds > 0 ? double(r.rays) / seconds : 0.0}};
  j["kernels"] = kernels;
  if (r.wavefront.slots) {
    j["wavefront"] = {{"slots", r.wavefront.slots}, {"bytes_per_path", r.wavefront.path_state_bytes},
                      {"simd_efficiency", r.simd_efficiency}};
    if (r.coherence) j["coherence"] = coherence_json(*r.coherence);
    nlohmann::json bounces = nlohmann::json::array();
    for (const auto& it : r.iterations)
      bounces.push_back({{"live_paths", it.live_paths}, {"extension_rays", it.live_paths},
                         {"shadow_rays", it.shadow_rays},
                         {"simd_efficiency", it.simd_groups ? it.simd_efficiency_sum / double(it.simd_groups) : 0.0},
                         {"kernel_seconds", it.kernel_seconds}});
    j["bounces"] = bounces;
  }
  if (denoise && denoise->denoised)
    j["denoise"] = {{"library", denoise->library},
                    {"seconds", denoise->seconds},
                    {"aov_seconds", denoise->aov_seconds}};
  return j;
}

}  // namespace cohort
