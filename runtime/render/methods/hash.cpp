// hash: sc+rg with the rays sorted by a hash of origin and direction before traversal (Garanzha &
// Loop 2010): the sort of pth without its partial traversal.
#include "runtime/render/stages/sorted_traversal.h"
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_hash(const MethodInputs& in) {
  WavefrontRender render(in, Launches::compacted);
  SortedTraversal sorted(render, RayOrder::hash);
  RenderResult result = render.run([&](WavefrontPass& p) {
    generate(p, Refill::every_bounce);
    if (sorted.sorts(p)) {
      sorted.walk(p);  // the hash code only: no subtree levels
      sorted.sort(p);
      sorted.resume(p);
    } else {
      extend(p);
    }
    shade(p);
    finish(p);
  });
  sorted.report(result);
  return result;
}

}  // namespace cohort
