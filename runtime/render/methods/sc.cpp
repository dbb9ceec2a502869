// sc: wavefront with stream compaction (Wald 2011): after every bounce the live slots are compacted
// into a queue, and the next bounce's launches cover that queue only.
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_sc(const MethodInputs& in) {
  WavefrontRender render(in, Launches::compacted);
  return render.run([](WavefrontPass& p) {
    if (p.live == 0) generate(p);
    if (p.live == 0) return false;
    extend(p);
    shade(p);
    finish(p);  // compacts the live slots into the queue
    return true;
  });
}

}  // namespace cohort
