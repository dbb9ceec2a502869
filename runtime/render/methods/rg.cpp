// rg: wavefront with path regeneration (Novák et al. 2010): after every bounce the free slots take
// new camera paths, so the pool stays full until the pass runs out of work items.
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_rg(const MethodInputs& in) {
  WavefrontRender render(in, Launches::all_slots);
  return render.run([](WavefrontPass& p) {
    generate(p, Refill::every_bounce);  // regeneration
    extend(p);
    shade(p);
    finish(p);
  });
}

}  // namespace cohort
