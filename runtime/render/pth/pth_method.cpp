// pth: the paper's method (Wang & Deng, "Mining Effective Parallelism from Hidden Coherence for GPU
// Based Path Tracing", Figure 3). On sc+rg, each bounce's rays walk the top KD-tree levels in local
// memory, which yields their coherence code (origin, PTH bits, direction); the codes are sorted on
// the device, and traversal resumes in sorted order from where the walk stopped
// (sorted_traversal_method.cpp, the bounce it shares with hash).
#include "runtime/render/methods/method.h"
#include "runtime/render/pth/sorted_traversal.h"

namespace cohort {

std::unique_ptr<PassLauncher> pth_method(const MethodInputs& in) { return sorted_traversal_method(in, RayOrder::pth); }

}  // namespace cohort
