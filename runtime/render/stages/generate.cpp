#include <algorithm>

#include "runtime/render/stages/stages.h"

namespace cohort {

void generate(WavefrontPass& p) {
  if (p.remaining == 0) return;
  WfGenerateArgs args;
  args.params = p.buffers.params;
  args.path = p.pool.path;
  args.counters = p.pool.counters;
  args.queue = p.pool.queue;
  args.use_queue = p.use_queue();
  args.slot_count = p.pool.slots;
  args.item_end = p.items;
  args.bind(p.kernels.generate);
  p.log.launch(p.device, p.kernels.generate, "generate", p.pool.slots);
  const std::uint64_t started = std::min<std::uint64_t>(p.pool.slots - p.live, p.remaining);
  p.remaining -= started;
  p.live += static_cast<std::uint32_t>(started);
}

}  // namespace cohort
