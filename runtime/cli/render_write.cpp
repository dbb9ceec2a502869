#include <fmt/format.h>
#include <fmt/ranges.h>

#include "runtime/cli/render_steps.h"
#include "runtime/image/image.h"
#include "runtime/render/run/adaptive.h"
#include "runtime/render/scene/scene_memory.h"
#include "runtime/util/atomic_file.h"

namespace cohort {
namespace {

// --verbose: every device's share, then the scene, the tree and the kernels of rank 0.
void print_details(const PreparedRender& render, const RenderOutcome& outcome) {
  const PreparedScene& prepared = render.scene;
  const RenderResult& result = outcome.result;
  for (const RankFigures& rank : outcome.ranks)
    for (const DeviceFigures& d : rank.devices)
      fmt::print("device{}: {} ({}): {} passes, {:.3f}s busy, {:.2f} Mrays/s\n",
                 outcome.ranks.size() > 1 ? fmt::format(" (rank {})", rank.rank) : std::string(), d.name, d.platform,
                 d.passes, d.busy_seconds, d.rays_per_second * 1e-6);
  fmt::print("scene: {} triangles, {} emissive, {} punctual lights, loaded in {:.3f}s\n",
             prepared.scene.triangle_count(), prepared.tables.emitters.entries.size(),
             prepared.tables.punctual.lights.size(), prepared.load_seconds);
  if (prepared.tables.environment)
    fmt::print("environment map: {}, {}x{}\n", prepared.tables.environment->source.string(),
               prepared.tables.environment->width, prepared.tables.environment->height);
  fmt::print("{}\n", describe_tree(prepared));
  fmt::print("device memory: {}\n",
             describe(scene_memory(prepared.tree, prepared.tables, prepared.bvh()), prepared.tree.triangles.size()));
  fmt::print("kernel compile: {:.3f}s ({})\n", result.compile_seconds, result.compile_from_cache ? "warm, from cache" : "cold");
  const auto features = prepared.tables.features.names();
  fmt::print("kernel features: {}\n", features.empty() ? std::string("none (Lambertian only)")
                                                       : fmt::format("{}", fmt::join(features, " ")));
  fmt::print("passes: {} of {} spp\n", result.passes, outcome.film.pass_samples);
  if (const double target = render.input.settings.target_error; target > 0) {
    const AdaptiveFigures f = adaptive_figures(outcome.film, target);
    fmt::print("adaptive: target error {}, estimated error {:.4f}, {} samples spent ({:.1f} spp mean, {}-{} per "
               "pixel), {} of {} {}x{} tiles stopped early, {} at their share of the target at the end\n",
               target, f.estimated_error, f.samples,
               double(f.samples) / double(std::max<std::size_t>(render.pixels(), 1)), f.min_pixel_samples,
               f.max_pixel_samples, f.tiles_stopped, f.tiles, kAdaptiveTile, kAdaptiveTile, f.tiles_converged);
  }
  for (const auto& [name, seconds] : result.kernel_seconds) fmt::print("kernel {}: {:.3f}s\n", name, seconds);
  if (const WavefrontFigures& w = result.wavefront; w.slots)
    fmt::print("wavefront: {} path slots x {} bytes = {:.1f} MiB, {} bounces, SIMD efficiency {:.3f}\n", w.slots,
               w.path_state_bytes, w.slots * w.path_state_bytes / 1048576.0, result.iterations.size(),
               result.simd_efficiency);
  if (const auto& c = result.coherence)
    fmt::print("coherence code: {} ({} bits), sorted from bounce {}; PTH subtree {} levels, {} nodes\n",
               c->sort.code, c->key_bits, c->sort.sort_from_bounce, c->sort.pth_levels, c->subtree_nodes);
  if (!result.auto_choice.method.empty()) {
    auto rates = [](const std::map<std::string, double>& by_method) {
      std::string text;
      for (const auto& [name, rate] : by_method) text += fmt::format("{}{} {:.2f}", text.empty() ? "" : ", ", name, rate * 1e-6);
      return text.empty() ? std::string("none") : text;
    };
    fmt::print("method auto: {}, {} ({:.3f}s of the render; Mrays/s at a quarter wave: {}; "
               "at a full wave, the fastest within 0.9x: {})\n",
               result.auto_choice.method, result.auto_choice.reason, result.auto_choice.probe_seconds,
               rates(result.auto_choice.probe_rays_per_second), rates(result.auto_choice.final_rays_per_second));
  }
}

}  // namespace

int write_render(const RenderCommand& cmd, const PreparedRender& render, const RenderOutcome& outcome,
                 const OutputPaths& out, const InterruptGuard& interrupt) {
  const RenderSettings& settings = render.input.settings;
  const RenderResult& result = outcome.result;
  std::vector<ExrLayer> aovs;
  if (outcome.aovs) aovs = aov_layers(*outcome.aovs, render.input.aovs);
  const bool adaptive = settings.target_error > 0;
  if (adaptive) {
    // each pixel's own sample count: the beauty is each pixel's sum over it
    const auto& counts = outcome.film.pixel_samples;
    aovs.push_back({{"samples"}, std::vector<float>(counts.begin(), counts.end())});
  }
  write_exr(out.exr, result.image, aovs);
  write_png(out.png, result.image);
  if (cmd.verbose) print_details(render, outcome);
  if (result.dropped_samples)
    fmt::print(stderr, "warning: {} NaN or infinite samples were dropped\n", result.dropped_samples);
  std::size_t device_count = 0;
  for (const RankFigures& rank : outcome.ranks) device_count += rank.devices.size();
  const std::size_t ranks = outcome.ranks.size();
  const double mrays = result.render_seconds > 0 ? double(result.rays) / result.render_seconds * 1e-6 : 0;
  std::string spp = fmt::format("{} spp", result.samples);
  if (adaptive) {
    const AdaptiveFigures f = adaptive_figures(outcome.film, settings.target_error);
    spp = fmt::format("{}-{} spp (mean {:.1f}; estimated relative error {:.4f}, target {})", f.min_pixel_samples,
                      f.max_pixel_samples, double(f.samples) / double(std::max<std::size_t>(render.pixels(), 1)),
                      f.estimated_error, settings.target_error);
  }
  fmt::print("rendered {}x{} at {} in {:.2f}s ({:.2f} Mrays/s{})\n", settings.width, settings.height, spp, result.render_seconds, mrays,
             device_count > 1 ? fmt::format(", {} devices in {} rank{}", device_count, ranks, ranks > 1 ? "s" : "")
                              : std::string());
  fmt::print("wrote {}\nwrote {}\n", out.exr.string(), out.png.string());
  if (cmd.checkpoint || cmd.resume) fmt::print("wrote {}\n", out.checkpoint.string());
  // denoised first, so that --stats records what the denoiser cost
  const DenoiseOutcome denoise = write_denoised(cmd, outcome, out);
  if (!cmd.stats_file.empty()) {
    write_file_atomically(cmd.stats_file, stats_json(render, outcome, &out, &denoise).dump(2) + "\n");
    fmt::print("wrote {}\n", cmd.stats_file);
  }
  if (denoise.code) return denoise.code;
  if (result.interrupted) {
    fmt::print(stderr, "interrupted by signal {} at {} spp: the image so far is saved{}\n", interrupt.signal_number(),
               result.samples, cmd.checkpoint || cmd.resume ? "; --resume continues it" : "");
    return 128 + interrupt.signal_number();
  }
  return 0;
}

void report_scene_warnings(const PreparedScene& prepared, const std::filesystem::path& path) {
  // the loaders name the file in most of their warnings already
  for (const auto& w : prepared.scene.warnings)
    fmt::print(stderr, "warning: {}{}\n", w.starts_with(path.string()) ? "" : path.string() + ": ", w);
  if (prepared.tree.stats.dropped_triangles)
    fmt::print(stderr, "warning: {}: dropped {} degenerate or non-finite triangles\n", path.string(),
               prepared.tree.stats.dropped_triangles);
}

}  // namespace cohort
