#include "runtime/render/stages/traversal_figures.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

namespace cohort {
namespace {

// The diagnostic of RenderSettings::straggler_rays: reads the nodes visited per launch index of an
// extension launch, and the rays of the worst `keep`.
void collect_stragglers(const Device& cl, const PathPool& pool, const DeviceBuffer* slots, std::uint32_t count,
                        std::size_t keep, PassOutput& out) {
  std::vector<std::uint32_t> steps(count), slot_of(count);
  cl.read(pool.steps, 0, count * sizeof(std::uint32_t), steps.data());
  if (slots) cl.read(*slots, 0, count * sizeof(std::uint32_t), slot_of.data());
  else std::iota(slot_of.begin(), slot_of.end(), 0u);
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  const std::size_t worst = std::min<std::size_t>(keep, count);
  std::partial_sort(order.begin(), order.begin() + worst, order.end(),
                    [&](std::uint32_t a, std::uint32_t b) { return steps[a] > steps[b]; });
  std::vector<StragglerRay> rays;
  for (std::size_t k = 0; k < worst && steps[order[k]] > 0; ++k) {
    std::array<co_float4, 2> ray{};
    cl.read(pool.path.path_org, std::size_t(slot_of[order[k]]) * sizeof(co_float4), sizeof(co_float4), &ray[0]);
    cl.read(pool.path.path_dir, std::size_t(slot_of[order[k]]) * sizeof(co_float4), sizeof(co_float4), &ray[1]);
    rays.push_back({steps[order[k]], {ray[0].x, ray[0].y, ray[0].z}, {ray[1].x, ray[1].y, ray[1].z}});
  }
  keep_worst(out.worst_rays, std::move(rays), keep);
  for (std::uint32_t s : steps)
    if (s > 0) out.extension_steps.push_back(s);  // 0: a free or finished slot, not a ray
}

}  // namespace

void measure_traversal(WavefrontPass& p, const DeviceBuffer* slots, std::uint32_t count) {
  if (p.settings.straggler_rays) {
    // a diagnostic that reads every ray's steps anyway: it may read the queue's length too
    std::uint32_t traced = count;
    if (p.use_queue()) {
      p.device.read(p.pool.counters, COUNTER_QUEUE * sizeof(std::uint32_t), sizeof(traced), &traced);
      ++p.out.host_reads;
    }
    collect_stragglers(p.device, p.pool, slots, std::min(traced, count), p.settings.straggler_rays, p.out);
    ++p.out.host_reads;
  }
  WfSimdEfficiencyArgs args;
  args.steps = p.pool.steps;
  args.count = count;
  args.counters = p.pool.counters;
  args.use_queue = p.use_queue();
  args.bind(p.kernels.simd_efficiency);
  p.log.launch(p.device, p.kernels.simd_efficiency, "simd efficiency", (count + SIMD_GROUP - 1) / SIMD_GROUP);
}

}  // namespace cohort
