// sc: wavefront with stream compaction (Wald 2011): after every bounce the live slots are compacted
// into a queue, and the next bounce's launches cover that queue only.
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_sc(const MethodInputs& in) {
  WavefrontRender render(in, Launches::compacted);
  return render.run([](WavefrontPass& p) {
    generate(p, Refill::when_drained);  // refills once the pool has drained
    extend(p);
    shade(p);
    finish(p);  // compacts the live slots into the queue
  });
}

}  // namespace cohort
