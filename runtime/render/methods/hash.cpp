// hash: sc+rg with the rays sorted by a hash of origin and direction before traversal (Garanzha &
// Loop 2010): the sort of pth without its partial traversal, so pth's bounce with the other key
// (runtime/render/pth/sorted_traversal_method.cpp).
#include "runtime/render/methods/method.h"
#include "runtime/render/pth/sorted_traversal.h"

namespace cohort {

std::unique_ptr<PassLauncher> hash_method(const MethodInputs& in) {
  return sorted_traversal_method(in, RayOrder::hash);  // the walk covers no subtree levels
}

}  // namespace cohort
