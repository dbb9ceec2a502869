// wavefront: one kernel per stage over every slot of the pool (Laine, Karras & Aila 2013); the pool
// takes new paths only when it has drained.
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_wavefront(const MethodInputs& in) {
  WavefrontRender render(in, Launches::all_slots);
  return render.run([](WavefrontPass& p) {
    if (p.live == 0) generate(p);
    if (p.live == 0) return false;
    extend(p);
    shade(p);
    finish(p);
    return true;
  });
}

}  // namespace cohort
