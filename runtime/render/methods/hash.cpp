// hash: sc+rg with the rays sorted by a hash of origin and direction before traversal (Garanzha &
// Loop 2010): the sort of pth without its partial traversal.
#include "runtime/render/stages/sorted_traversal.h"
#include "runtime/render/stages/stages.h"

namespace cohort {

std::unique_ptr<PassLauncher> hash_method(const MethodInputs& in) {
  auto render = std::make_unique<WavefrontRender>(in, Launches::compacted);
  auto sorted = std::make_shared<SortedTraversal>(*render, RayOrder::hash);
  render->set_bounce(
      [sorted](WavefrontPass& p) {
        generate(p, Refill::every_bounce);
        if (sorted->sorts(p)) {
          sorted->walk(p);  // the hash code only: no subtree levels
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
