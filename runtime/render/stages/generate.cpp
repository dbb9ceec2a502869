#include "runtime/render/stages/stages.h"

namespace cohort {

void generate(WavefrontPass& p, Refill refill) {
  if (!p.items_left) return;
  WfGenerateArgs args;
  args.params = p.buffers.params;
  args.path = p.pool.path;
  args.counters = p.pool.counters;
  args.queue = p.pool.queue;
  args.use_queue = p.use_queue();
  args.slot_count = p.pool.slots;
  args.item_end = p.items;
  args.regenerate = refill == Refill::every_bounce ? 1u : 0u;
  args.pixel_list = p.buffers.pixel_list;
  args.bind(p.kernels.generate);
  p.log.launch(p.device, p.kernels.generate, "generate", p.pool.slots);
}

}  // namespace cohort
