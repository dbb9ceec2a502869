// rg: wavefront with path regeneration (Novák et al. 2010): after every bounce the free slots take
// new camera paths, so the pool stays full until the pass runs out of work items.
#include "runtime/render/stages/stages.h"

namespace cohort {

std::unique_ptr<PassLauncher> rg_method(const MethodInputs& in) {
  auto render = std::make_unique<WavefrontRender>(in, Launches::all_slots);
  render->set_bounce([](WavefrontPass& p) {
    generate(p, Refill::every_bounce);  // regeneration
    extend(p);
    shade(p);
    finish(p);
  });
  return render;
}

}  // namespace cohort
