#include "runtime/render/stages/wavefront_loop.h"

#include <algorithm>
#include <array>

#include "kernels/common/contract.h"

namespace cohort {
namespace {

// Source of the non-blocking counter resets: the host memory of a non-blocking write must outlive
// the command, so it cannot be a local of the loop.
constexpr std::array<std::uint32_t, COUNTER_COUNT> kZeros{};

// A launch holds one result per (pixel, sample): bound it to ~64 MiB of results, and to the
// render's spp, which no launch exceeds (small renders then allocate little: Oclgrind's checks
// cost time in proportion to the memory allocated, at every launch).
std::uint32_t max_samples_per_pass(const RenderSettings& s, std::uint32_t pixels) {
  std::uint32_t most = std::max<std::uint32_t>(1, (1u << 22) / std::max<std::uint32_t>(pixels, 1));
  if (s.spp > 0) most = std::min(most, s.spp);
  return most;
}

}  // namespace

// The scene's feature options go to every program that shades or traces, so all methods compile
// the shared code identically.
WavefrontRender::WavefrontRender(const MethodInputs& in, Launches launches, std::size_t sort_bytes_per_slot)
    : in_(in),
      launches_(launches),
      program_(in.device.build_program(in.cache, "wavefront", in.scene.build_options)),
      pixels_(in.settings.width * in.settings.height),
      max_per_pass_(max_samples_per_pass(in.settings, pixels_)),
      pool_(in.device,
            choose_pool_size(in.device, in.settings,
                             std::uint64_t(pixels_) * std::min(max_per_pass_, std::max<std::uint32_t>(in.settings.spp, 1)),
                             WAVEFRONT_SLOT_BYTES + sort_bytes_per_slot)),
      results_(in.device.allocate("pass results", std::size_t(pixels_) * max_per_pass_ * sizeof(co_float4))),
      scene_(in.scene.kernel_buffers()) {
  kernels_.generate = program_.kernel("wf_generate");
  kernels_.extend = program_.kernel("wf_extend");
  kernels_.shade = program_.kernel("wf_shade");
  kernels_.shadow = program_.kernel("wf_shadow");
  kernels_.finish = program_.kernel("wf_finish");
  kernels_.accumulate = program_.kernel("wf_accumulate");
  kernels_.simd_efficiency = program_.kernel("wf_simd_efficiency");
  kernels_.shadow_max_steps = program_.kernel("wf_shadow_max_steps");
}

RenderResult WavefrontRender::run(const BounceStages& bounce) {
  const Device& cl = in_.device;
  std::vector<IterationStats> iterations;
  auto pass = [&](const PassBuffers& b, const RenderParams& p) {
    WavefrontPass wp{cl, in_.settings, pool_, kernels_, scene_, b, results_, launches_};
    wp.items = pixels_ * p.samples_per_pass;
    wp.remaining = wp.items;
    std::array<std::uint32_t, COUNTER_COUNT> counters{};
    cl.write(pool_.counters, 0, sizeof(kZeros), kZeros.data(), false);
    for (std::size_t iteration = 0;; ++iteration) {
      wp.bounce = static_cast<std::uint32_t>(iteration) + 1;
      if (!bounce(wp)) break;
      cl.read(pool_.counters, 0, sizeof(counters), counters.data());
      // the per-bounce counters, from the shadow rays through the SIMD groups
      cl.write(pool_.counters, COUNTER_SHADOW * sizeof(std::uint32_t),
               (COUNTER_SIMD_GROUPS - COUNTER_SHADOW + 1) * sizeof(std::uint32_t), kZeros.data(), false);

      if (iterations.size() <= iteration) iterations.resize(iteration + 1);
      IterationStats& stats = iterations[iteration];
      stats.live_paths += wp.live;
      stats.shadow_rays += counters[COUNTER_SHADOW];
      stats.simd_groups += counters[COUNTER_SIMD_GROUPS];
      stats.simd_efficiency_sum += counters[COUNTER_SIMD_SUM] * 1e-4;
      auto seconds = wp.log.collect();
      add_seconds(seconds, wp.sort_seconds);
      wp.sort_seconds.clear();
      add_seconds(stats.kernel_seconds, seconds);
      add_seconds(wp.out.kernel_seconds, seconds);
      wp.out.rays += wp.live + counters[COUNTER_SHADOW];
      wp.out.max_steps = std::max(wp.out.max_steps, counters[COUNTER_MAX_STEPS]);
      wp.live = counters[COUNTER_QUEUE];
    }
    WfAccumulateArgs accumulate;
    accumulate.params = b.params;
    accumulate.results = results_;
    accumulate.film = b.film;
    accumulate.dropped_samples = b.dropped;
    accumulate.bind(kernels_.accumulate);
    wp.log.launch(cl, kernels_.accumulate, "accumulate", pixels_);
    add_seconds(wp.out.kernel_seconds, wp.log.collect());
    return std::move(wp.out);
  };
  RenderResult result =
      drive_passes(cl, in_.cache, in_.params, in_.settings, max_per_pass_, in_.progress, in_.control, pass);
  result.compile_seconds = program_.seconds;
  result.compile_from_cache = program_.from_cache;
  std::uint64_t groups = 0;
  double efficiency = 0;
  for (const auto& i : iterations) {
    groups += i.simd_groups;
    efficiency += i.simd_efficiency_sum;
  }
  result.simd_efficiency = groups ? efficiency / double(groups) : 0;
  result.iterations = std::move(iterations);
  result.wavefront_size = pool_.slots;
  result.path_state_bytes = WAVEFRONT_SLOT_BYTES;
  return result;
}

}  // namespace cohort
