#include "runtime/render/pass_driver.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include <fmt/format.h>

#include "runtime/cl/cl_error.h"
#include "runtime/render/launch_log.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

FilmState read_film(const Device& cl, const PassBuffers& b, const RenderSettings& s, std::uint32_t samples) {
  FilmState film;
  film.width = s.width;
  film.height = s.height;
  film.samples = samples;
  film.sums.resize(std::size_t(s.width) * s.height);
  cl.read(b.film, 0, film.sums.size() * sizeof(co_float4), film.sums.data());
  std::uint32_t dropped = 0;
  cl.read(b.dropped, 0, sizeof(dropped), &dropped);
  film.dropped_samples = dropped;
  return film;
}

Image to_image(const FilmState& film) {
  Image image(static_cast<int>(film.width), static_cast<int>(film.height));
  const float inv = film.samples ? 1.f / static_cast<float>(film.samples) : 0.f;
  for (std::size_t i = 0; i < film.sums.size(); ++i) {
    image.rgb[3 * i + 0] = film.sums[i].x * inv;
    image.rgb[3 * i + 1] = film.sums[i].y * inv;
    image.rgb[3 * i + 2] = film.sums[i].z * inv;
  }
  return image;
}

}  // namespace

RenderResult drive_passes(const Device& cl, const RenderParams& base_params, const RenderSettings& settings,
                          std::uint32_t max_samples_per_pass, const ProgressCallback& progress,
                          const RenderControl& control, const PassFunction& pass) {
  using Clock = std::chrono::steady_clock;
  RenderResult result;
  const std::uint32_t pixels = settings.width * settings.height;
  PassBuffers buffers;
  buffers.params = cl.allocate("render parameters", sizeof(RenderParams), nullptr, Access::read_only);
  std::vector<co_float4> start(pixels, co_float4{0, 0, 0, 0});
  std::uint32_t start_dropped = 0;
  if (control.resume_from) {
    const FilmState& f = *control.resume_from;
    if (f.width != settings.width || f.height != settings.height || f.sums.size() != pixels)
      throw InputError(fmt::format("the checkpoint is {}x{}, the render {}x{}", f.width, f.height, settings.width,
                                   settings.height));
    start = f.sums;
    start_dropped = static_cast<std::uint32_t>(f.dropped_samples);
    result.samples = result.resumed_samples = f.samples;
  }
  buffers.film = cl.allocate("film", start.size() * sizeof(co_float4), start.data());
  buffers.dropped = cl.allocate("dropped-sample counter", sizeof(start_dropped), &start_dropped);

  RenderParams params = base_params;
  const bool unbounded = settings.time_limit > 0 && settings.spp == 0;
  const auto t0 = Clock::now();
  double last_checkpoint = 0;
  std::uint32_t per_pass = 1;
  while (unbounded || result.samples < settings.spp) {
    const std::uint32_t count = unbounded ? per_pass : std::min(per_pass, settings.spp - result.samples);
    params.sample_offset = result.samples;
    params.samples_per_pass = count;
    cl.write(buffers.params, 0, sizeof(params), &params);
    const PassOutput out = pass(buffers, params);
    result.rays += out.rays;
    add_seconds(result.kernel_seconds, out.kernel_seconds);
    result.samples += count;
    result.render_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (progress) progress({result.samples, unbounded ? 0u : settings.spp, result.rays, result.render_seconds});
    if (control.stop_requested && control.stop_requested()) {
      result.interrupted = true;
      break;
    }
    if (settings.time_limit > 0 && result.render_seconds >= settings.time_limit) break;
    if (control.checkpoint && control.checkpoint_seconds > 0 &&
        result.render_seconds - last_checkpoint >= control.checkpoint_seconds) {
      control.checkpoint(read_film(cl, buffers, settings, result.samples));
      last_checkpoint = result.render_seconds;
    }
    // grow passes while they are short, so progress stays live without per-pass overhead
    double pass_seconds = 0;
    for (const auto& [name, s] : out.kernel_seconds) pass_seconds += s;
    if (pass_seconds < 0.25 && per_pass * 2 <= max_samples_per_pass) per_pass *= 2;
  }
  const FilmState film = read_film(cl, buffers, settings, result.samples);
  if (control.checkpoint) control.checkpoint(film);
  result.dropped_samples = film.dropped_samples;
  result.image = to_image(film);
  return result;
}

}  // namespace cohort
