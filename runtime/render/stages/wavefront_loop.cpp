#include "runtime/render/stages/wavefront_loop.h"

#include <algorithm>
#include <array>

#include "kernels/common/core/contract.h"

namespace cohort {
namespace {

// Source of the non-blocking counter reset: the host memory of a non-blocking write must outlive
// the command, so it cannot be a local of the loop. (The bounce rows after the counters are
// written before they are read.)
constexpr std::array<std::uint32_t, COUNTER_COUNT> kZeros{};

// Bounces enqueued between two reads of the counters. A read waits for the device to drain, and
// only tells whether the pass is over; the bounces enqueued after its last path ended cost their
// launches (every work item leaves at once). Without regeneration a wave takes up to max-depth
// bounces, with regeneration as many as its items need: there is no useful bound to run to
// blind, so the loop reads every few bounces. Once every item is handed out the launches cover only
// the live paths the last read found, so bounces past the end cost little: the interval doubles
// then, for the long tail of paths that Russian roulette spares.
constexpr std::size_t kBouncesPerRead = 4;
static_assert(kBouncesPerRead <= BOUNCE_ROWS, "the rows of the bounces between two reads must fit the ring");

// Bounces before the pass's first read. When the pool holds every item of the pass and paths have
// at most max_depth segments, every path has ended after max_depth bounces: one read then ends the
// pass (instead of a read after 4 bounces that only learns that the fifth is still to come).
std::size_t first_read_interval(const RenderSettings& s, std::uint32_t items, std::uint32_t slots) {
  if (s.max_depth == 0 || items > slots) return kBouncesPerRead;
  return std::min<std::size_t>(s.max_depth, BOUNCE_ROWS);
}

// A pass holds one result per (pixel, sample): ~4M results (64 MiB), or 4 per path slot where the
// pool is larger, so that regeneration keeps a wave full for several refills; and no more than
// the render's spp, which no pass exceeds (small renders then allocate little: Oclgrind's checks
// cost time in proportion to the memory allocated, at every launch).
std::uint32_t max_samples_per_pass(const RenderSettings& s, std::uint32_t pixels, std::uint32_t pool_slots) {
  const std::uint64_t results = std::max<std::uint64_t>(1u << 22, std::uint64_t(4) * pool_slots);
  std::uint32_t most = static_cast<std::uint32_t>(
      std::clamp<std::uint64_t>(results / std::max<std::uint32_t>(pixels, 1), 1, UINT32_MAX));
  if (s.spp > 0) most = std::min(most, s.spp);
  return most;
}

}  // namespace

WavefrontMemory::WavefrontMemory(const Device& device, const RenderSettings& s)
    : max_per_launch(max_samples_per_pass(s, s.width * s.height, device_pool_size(device.info(), s))),
      // no more slots than a launch has work items
      pool(device, static_cast<std::uint32_t>(std::min<std::uint64_t>(
                       device_pool_size(device.info(), s),
                       std::uint64_t(s.width) * s.height * std::min(max_per_launch, std::max<std::uint32_t>(s.spp, 1))))),
      results(device.allocate("pass results", std::size_t(s.width) * s.height * max_per_launch * sizeof(co_float4))) {}

// The scene's feature options go to every program that shades or traces, so all methods compile
// the shared code identically.
WavefrontRender::WavefrontRender(const MethodInputs& in, Launches launches)
    : in_(in),
      launches_(launches),
      program_(in.device.build_program(in.cache, "wavefront", in.scene.build_options)),
      memory_(in.wavefront_memory ? in.wavefront_memory : std::make_shared<WavefrontMemory>(in.device, in.settings)),
      scene_(in.scene.kernel_buffers()) {
  kernels_.generate = program_.kernel("wf_generate");
  kernels_.extend = program_.kernel("wf_extend");
  kernels_.shade = program_.kernel("wf_shade");
  kernels_.shadow = program_.kernel("wf_shadow");
  kernels_.finish = program_.kernel("wf_finish");
  kernels_.accumulate = program_.kernel("wf_accumulate");
  kernels_.simd_efficiency = program_.kernel("wf_simd_efficiency");
  kernels_.shadow_max_steps = program_.kernel("wf_shadow_max_steps");
  kernels_.end_bounce = program_.kernel("wf_end_bounce");
}

void WavefrontRender::set_bounce(BounceStages bounce, std::function<void(RenderResult&)> report) {
  bounce_ = std::move(bounce);
  report_ = std::move(report);
}

PassOutput WavefrontRender::launch(const PassBuffers& b, const RenderParams& p) {
  const Device& cl = in_.device;
  PathPool& pool = memory_->pool;
  WavefrontPass wp{cl, in_.settings, pool, kernels_, scene_, b, memory_->results, launches_};
  const std::uint32_t pass_pixels = pass_pixel_count(&p);
  wp.items = pass_pixels * p.samples_per_pass;
  wp.live_bound = pool.slots;
  cl.write(pool.counters, 0, sizeof(kZeros), kZeros.data(), false);
  std::vector<LaunchLog> unread;  // the launches of the bounces since the last read, by bounce
  std::array<std::uint32_t, COUNTER_WORDS> words{};
  std::size_t interval = first_read_interval(in_.settings, wp.items, pool.slots);
  for (bool over = false; !over; ++wp.bounce) {
    bounce_(wp);
    unread.push_back(std::move(wp.log));
    wp.log = LaunchLog{};
    if (unread.size() < interval) continue;
    // the one blocking read: the counters and the rows of the bounces since the last read
    cl.read(pool.counters, 0, sizeof(words), words.data());
    ++wp.out.host_reads;
    wp.items_left = words[COUNTER_NEXT_ITEM] < wp.items;
    if (!wp.items_left) {
      wp.live_bound = words[COUNTER_QUEUE];  // the paths that survived the last bounce
      interval = std::min<std::size_t>(interval * 2, BOUNCE_ROWS);
    }
    over = !wp.items_left && words[COUNTER_QUEUE] == 0;
    const std::uint32_t first = wp.bounce + 1 - static_cast<std::uint32_t>(unread.size());
    for (std::uint32_t k = 0; k < unread.size(); ++k) {
      const std::uint32_t bounce = first + k;
      const std::uint32_t* row = &words[COUNTER_COUNT + (bounce % BOUNCE_ROWS) * BOUNCE_FIGURES];
      const auto seconds = unread[k].collect();
      add_seconds(wp.out.kernel_seconds, seconds);
      // a bounce that traced nothing ran after the pass was over (its launches left at once)
      if (row[BOUNCE_LIVE] == 0) continue;
      if (iterations_.size() <= bounce) iterations_.resize(bounce + 1);
      IterationStats& stats = iterations_[bounce];
      stats.live_paths += row[BOUNCE_LIVE];
      stats.shadow_rays += row[BOUNCE_SHADOW];
      stats.simd_groups += row[BOUNCE_SIMD_GROUPS];
      stats.simd_efficiency_sum += row[BOUNCE_SIMD_SUM] * 1e-4;
      add_seconds(stats.kernel_seconds, seconds);
      wp.out.rays += row[BOUNCE_LIVE] + row[BOUNCE_SHADOW];
    }
    unread.clear();
  }
  wp.out.max_steps = words[COUNTER_MAX_STEPS];
  WfAccumulateArgs accumulate;
  accumulate.params = b.params;
  accumulate.results = memory_->results;
  accumulate.film = b.film;
  accumulate.dropped_samples = b.dropped;
  accumulate.pixel_list = b.pixel_list;
  accumulate.bind(kernels_.accumulate);
  wp.log.launch(cl, kernels_.accumulate, "accumulate", pass_pixels);
  add_seconds(wp.out.kernel_seconds, wp.log.collect());
  return std::move(wp.out);
}

void WavefrontRender::report(RenderResult& result) const {
  result.compile_seconds += program_.seconds;
  result.compile_from_cache = program_.from_cache;
  std::uint64_t groups = 0;
  double efficiency = 0;
  for (const auto& i : iterations_) {
    groups += i.simd_groups;
    efficiency += i.simd_efficiency_sum;
  }
  result.simd_efficiency = groups ? efficiency / double(groups) : 0;
  result.iterations = iterations_;
  result.wavefront = {.slots = memory_->pool.slots, .path_state_bytes = WAVEFRONT_SLOT_BYTES};
  if (report_) report_(result);
}

}  // namespace cohort
