#include "runtime/render/stages/stages.h"

namespace cohort {

void finish(WavefrontPass& p) {
  // the bounce's figures, and wf_finish counts the live slots from zero
  WfEndBounceArgs end;
  end.counters = p.pool.counters;
  end.bounce = p.bounce;
  end.bind(p.kernels.end_bounce);
  p.log.launch(p.device, p.kernels.end_bounce, "end bounce", 1, 1);
  WfFinishArgs args;
  args.path = p.pool.path;
  args.results = p.results;
  args.counters = p.pool.counters;
  args.queue = p.pool.queue;
  args.use_queue = p.use_queue();
  args.slot_count = p.pool.slots;
  args.bind(p.kernels.finish);
  p.log.launch(p.device, p.kernels.finish, "finish", p.pool.slots);
}

}  // namespace cohort
