// An 8-wide BVH with float planes over the KD-tree's kept triangles, in the device layout of
// kernels/common/core/types.h (Bvh8fNode, 256 bytes): --tree bvh8f, traced by
// kernels/common/accel/bvh8f_traverse.h with eight boxes per float8 step, for CPUs. The 4-wide BVH's
// collapse at width 8, its leaves the 4-wide BVH's (the same kept triangles), so every ray gets the
// same hit from it as from any other tree.
#pragma once

#include <span>
#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/accel/bvh4.h"

namespace cohort {

// The 4-wide BVH's figures (node_count counts 8-wide nodes).
using Bvh8fStats = Bvh4Stats;

struct Bvh8f {
  // Node 0 is the root; each node before its children, depth first (each subtree contiguous).
  std::vector<Bvh8fNode> nodes;
  // The leaves' entries (a leaf reference names its first entry and count): each a copy of a kept
  // triangle, with that triangle's index in v0.w, as the 4-wide BVH's.
  std::vector<Triangle> leaf_vertices;
  Bvh8fStats stats;
};

// The binary SAH tree of runtime/accel/binary_bvh.h (leaves of at most four references, as the
// 4-wide BVH's) collapsed into 8-wide nodes (runtime/accel/wide_collapse.h). The same tree for any
// thread count. Throws InputError for an empty input or more references than a leaf can name.
Bvh8f build_bvh8f(std::span<const Triangle> triangles);

}  // namespace cohort
