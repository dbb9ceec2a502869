// The bounce of the ray-sorting methods: sc+rg with `extend` replaced by SortedTraversal's walk,
// sort and resume (sorted_traversal.h). pth (pth_method.cpp) sorts by the coherence code of the
// paper, hash (runtime/render/methods/hash.cpp) by a hash of origin and direction.
#include "runtime/render/methods/method.h"
#include "runtime/render/pth/sorted_traversal.h"
#include "runtime/render/stages/stages.h"

namespace cohort {

std::unique_ptr<PassLauncher> sorted_traversal_method(const MethodInputs& in, RayOrder order) {
  auto render = std::make_unique<WavefrontRender>(in, Launches::compacted);
  auto sorted = std::make_shared<SortedTraversal>(*render, order);
  render->set_bounce(
      [sorted](WavefrontPass& p) {
        generate(p, Refill::every_bounce);
        if (sorted->sorts(p)) {
          sorted->walk(p);  // partial traversal heuristic and coherence code (hash: the code only)
          sorted->sort(p);
          sorted->resume(p);
        } else {
          extend(p);
        }
        shade(p);
        finish(p);
      },
      [sorted](RenderResult& result) { sorted->report(result); });
  return render;
}

}  // namespace cohort
