// sc: wavefront with stream compaction (Wald 2011): after every bounce the live slots are compacted
// into a queue, and the next bounce's launches cover that queue only.
#include "runtime/render/stages/stages.h"

namespace cohort {

std::unique_ptr<PassLauncher> sc_method(const MethodInputs& in) {
  auto render = std::make_unique<WavefrontRender>(in, Launches::compacted);
  render->set_bounce([](WavefrontPass& p) {
    generate(p, Refill::when_drained);  // refills once the pool has drained
    extend(p);
    shade(p);
    finish(p);  // compacts the live slots into the queue
  });
  return render;
}

}  // namespace cohort
