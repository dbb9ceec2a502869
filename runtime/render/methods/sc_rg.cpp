// sc+rg: stream compaction and path regeneration together (van Antwerpen 2011): launches cover the
// queue of live paths, and free slots take new paths after every bounce.
#include "runtime/render/stages/stages.h"

namespace cohort {

std::unique_ptr<PassLauncher> sc_rg_method(const MethodInputs& in) {
  auto render = std::make_unique<WavefrontRender>(in, Launches::compacted);
  render->set_bounce([](WavefrontPass& p) {
    generate(p, Refill::every_bounce);  // regeneration
    extend(p);
    shade(p);
    finish(p);  // compaction
  });
  return render;
}

}  // namespace cohort
