// hash: sc+rg with the rays sorted by a hash of origin and direction before traversal (Garanzha &
// Loop 2010): the sort of pth without its partial traversal, so pth's bounce (pth.cpp) with the
// other key.
#include "runtime/render/methods/method.h"
#include "runtime/render/stages/sorted_traversal.h"

namespace cohort {

std::unique_ptr<PassLauncher> hash_method(const MethodInputs& in) {
  return sorted_traversal_method(in, RayOrder::hash);  // the walk covers no subtree levels
}

}  // namespace cohort
