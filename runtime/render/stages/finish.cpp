#include <array>

#include "runtime/render/stages/stages.h"

namespace cohort {

void finish(WavefrontPass& p) {
  // wf_finish counts the live slots from zero (the host memory of a non-blocking write must outlive
  // the command)
  static constexpr std::array<std::uint32_t, 1> kZero{};
  p.device.write(p.pool.counters, COUNTER_QUEUE * sizeof(std::uint32_t), sizeof(kZero), kZero.data(), false);
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
