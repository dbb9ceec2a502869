// pth: the paper's method (Wang & Deng, "Mining Effective Parallelism from Hidden Coherence for GPU
// Based Path Tracing", Figure 3). On sc+rg, each bounce's rays walk the top KD-tree levels in local
// memory, which yields their coherence code (origin, PTH bits, direction); the codes are sorted on
// the device, and traversal resumes in sorted order from where the walk stopped.
#include "runtime/render/stages/sorted_traversal.h"
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_pth(const MethodInputs& in) {
  WavefrontRender render(in, Launches::compacted);
  SortedTraversal sorted(render, RayOrder::pth);
  RenderResult result = render.run([&](WavefrontPass& p) {
    generate(p, Refill::every_bounce);
    if (sorted.sorts(p)) {
      sorted.walk(p);  // partial traversal heuristic and coherence code
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
