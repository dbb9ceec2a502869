// pth: the paper's method (Wang & Deng, "Mining Effective Parallelism from Hidden Coherence for GPU
// Based Path Tracing", Figure 3). On sc+rg, each bounce's rays walk the top KD-tree levels in local
// memory, which yields their coherence code (origin, PTH bits, direction); the codes are sorted on
// the device, and traversal resumes in sorted order from where the walk stopped.
#include "runtime/render/stages/sorted_traversal.h"
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

std::unique_ptr<PassLauncher> pth_method(const MethodInputs& in) { return sorted_traversal_method(in, RayOrder::pth); }

}  // namespace cohort
