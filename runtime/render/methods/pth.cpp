// pth: the paper's method (Wang & Deng, "Mining Effective Parallelism from Hidden Coherence for GPU
// Based Path Tracing", Figure 3). On sc+rg, each bounce's rays walk the top KD-tree levels in local
// memory, which yields their coherence code (origin, PTH bits, direction); the codes are sorted on
// the device, and traversal resumes in sorted order from where the walk stopped.
#include "runtime/render/stages/sorted_traversal.h"
#include "runtime/render/stages/stages.h"

namespace cohort {

RenderResult render_pth(const MethodInputs& in) {
  WavefrontRender render(in, Launches::compacted, SORT_SLOT_BYTES);
  SortedTraversal sorted(render, SortedBy::pth);
  RenderResult result = render.run([&](WavefrontPass& p) {
    generate(p);
    if (p.live == 0) return false;
    if (sorted.sorts(p)) {
      sorted.walk(p);  // partial traversal heuristic and coherence code
      sorted.sort(p);
      sorted.resume(p);
    } else {
      extend(p);
    }
    shade(p);
    finish(p);
    return true;
  });
  sorted.report(result);
  return result;
}

}  // namespace cohort
