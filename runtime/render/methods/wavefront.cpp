// wavefront: one kernel per stage over every slot of the pool (Laine, Karras & Aila 2013); the pool
// takes new paths only when it has drained.
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_wavefront(const MethodInputs& in) {
  WavefrontRender render(in, Launches::all_slots);
  return render.run([](WavefrontPass& p) {
    generate(p, Refill::when_drained);  // refills once the pool has drained
    extend(p);
    shade(p);
    finish(p);
  });
}

}  // namespace cohort
