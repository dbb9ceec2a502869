// build_bvh8f: the binary BVH of runtime/accel/binary_bvh.h collapsed into 8-wide nodes with float
// planes, depth first (runtime/accel/wide_collapse.h, the 4-wide BVH's collapse at width 8).
#include "runtime/accel/bvh8f.h"

#include <chrono>

#include "runtime/accel/wide_collapse.h"

namespace cohort {

Bvh8f build_bvh8f(std::span<const Triangle> triangles) {
  const auto start = std::chrono::steady_clock::now();
  Bvh8f bvh;
  wide_collapse::build<8>(bvh, triangles, "8-wide BVH (--tree bvh8f)");
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace cohort
