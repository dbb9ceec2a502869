// wavefront: one kernel per stage over every slot of the pool (Laine, Karras & Aila 2013); the pool
// takes new paths only when it has drained.
#include "runtime/render/stages/stages.h"

namespace cohort {

std::unique_ptr<PassLauncher> wavefront_method(const MethodInputs& in) {
  auto render = std::make_unique<WavefrontRender>(in, Launches::all_slots);
  render->set_bounce([](WavefrontPass& p) {
    generate(p, Refill::when_drained);  // refills once the pool has drained
    extend(p);
    shade(p);
    finish(p);
  });
  return render;
}

}  // namespace cohort
