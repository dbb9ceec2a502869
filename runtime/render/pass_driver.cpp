#include "runtime/render/pass_driver.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "runtime/cl/cl_error.h"
#include "runtime/render/launch_log.h"

namespace cohort {

RenderResult drive_passes(const ClContext& cl, const RenderParams& base_params, const RenderSettings& settings,
                          std::uint32_t max_samples_per_pass, const ProgressCallback& progress,
                          const PassFunction& pass) {
  using Clock = std::chrono::steady_clock;
  RenderResult result;
  const std::uint32_t pixels = settings.width * settings.height;
  PassBuffers buffers;
  buffers.params = cl.buffer("render parameters", sizeof(RenderParams), nullptr, CL_MEM_READ_ONLY);
  const std::vector<co_float4> zeros(pixels, co_float4{0, 0, 0, 0});
  buffers.film = cl.buffer("film", zeros.size() * sizeof(co_float4), zeros.data());
  const std::uint32_t zero = 0;
  buffers.dropped = cl.buffer("dropped-sample counter", sizeof(zero), &zero);

  RenderParams params = base_params;
  const bool unbounded = settings.time_limit > 0 && settings.spp == 0;
  const auto t0 = Clock::now();
  std::uint32_t per_pass = 1;
  while (unbounded || result.samples < settings.spp) {
    const std::uint32_t count = unbounded ? per_pass : std::min(per_pass, settings.spp - result.samples);
    params.sample_offset = result.samples;
    params.samples_per_pass = count;
    cl.queue.enqueueWriteBuffer(buffers.params, CL_TRUE, 0, sizeof(params), &params);
    const PassOutput out = pass(buffers, params);
    result.rays += out.rays;
    add_seconds(result.kernel_seconds, out.kernel_seconds);
    result.samples += count;
    result.render_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (progress) progress({result.samples, unbounded ? 0u : settings.spp, result.rays, result.render_seconds});
    if (settings.time_limit > 0 && result.render_seconds >= settings.time_limit) break;
    // grow passes while they are short, so progress stays live without per-pass overhead
    double pass_seconds = 0;
    for (const auto& [name, s] : out.kernel_seconds) pass_seconds += s;
    if (pass_seconds < 0.25 && per_pass * 2 <= max_samples_per_pass) per_pass *= 2;
  }
  std::vector<co_float4> sums(pixels);
  cl.queue.enqueueReadBuffer(buffers.film, CL_TRUE, 0, sums.size() * sizeof(co_float4), sums.data());
  std::uint32_t dropped = 0;
  cl.queue.enqueueReadBuffer(buffers.dropped, CL_TRUE, 0, sizeof(dropped), &dropped);
  result.dropped_samples = dropped;
  result.image = Image(static_cast<int>(settings.width), static_cast<int>(settings.height));
  const float inv = result.samples ? 1.f / static_cast<float>(result.samples) : 0.f;
  for (std::uint32_t i = 0; i < pixels; ++i) {
    result.image.rgb[3 * i + 0] = sums[i].x * inv;
    result.image.rgb[3 * i + 1] = sums[i].y * inv;
    result.image.rgb[3 * i + 2] = sums[i].z * inv;
  }
  return result;
}

}  // namespace cohort
