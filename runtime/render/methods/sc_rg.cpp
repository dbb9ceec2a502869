// sc+rg: stream compaction and path regeneration together (van Antwerpen 2011): launches cover the
// queue of live paths, and free slots take new paths after every bounce.
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_sc_rg(const MethodInputs& in) {
  WavefrontRender render(in, Launches::compacted);
  return render.run([](WavefrontPass& p) {
    generate(p, Refill::every_bounce);  // regeneration
    extend(p);
    shade(p);
    finish(p);  // compaction
  });
}

}  // namespace cohort
