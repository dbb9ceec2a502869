#include "runtime/render/stages/stages.h"
#include "runtime/render/stages/traversal_figures.h"

namespace cohort {

void extend(WavefrontPass& p) {
  const std::uint32_t count = p.count();
  WfExtendArgs args;
  args.params = p.buffers.params;
  args.scene = p.scene;
  args.path = p.pool.path;
  args.hits = p.pool.hits;
  args.queue = p.pool.queue;
  args.use_queue = p.use_queue();
  args.count = count;
  args.steps = p.pool.steps;
  args.counters = p.pool.counters;
  args.bind(p.kernels.extend);
  p.log.launch(p.device, p.kernels.extend, "extend", count);
  measure_traversal(p, p.use_queue() ? &p.pool.queue : nullptr, count);
}

}  // namespace cohort
