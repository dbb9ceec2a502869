// An 8-wide BVH with float planes over the KD-tree's kept triangles, in the device layout of
// kernels/common/core/types.h (Bvh8fNode, 256 bytes): --tree bvh8f, traced by
// kernels/common/accel/bvh8f_traverse.h with eight boxes per float8 step and four triangles per
// float4 step, for CPUs. The 4-wide BVH's collapse at width 8 of a binary SAH tree whose leaves hold
// up to four of the kept triangles in a block (Triangle4), so every ray gets the same hit from it as
// from any other tree.
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
  // The leaves' triangles, four to a block (a leaf reference names its first block and its triangle
  // count; a leaf of n triangles takes ceil(n / 4) blocks): copies of kept triangles, lane by lane,
  // with their indices, the unused lanes of a leaf's last block a copy of its last triangle.
  std::vector<Triangle4> leaf_blocks;
  Bvh8fStats stats;
};

// The binary SAH tree of runtime/accel/binary_bvh.h (leaves of at most four references, costed as
// one block of four: binary_bvh::LeafShape) collapsed into 8-wide nodes (runtime/accel/wide_collapse.h).
// The same tree for any thread count. Throws InputError for an empty input or more references than a leaf can name.
Bvh8f build_bvh8f(std::span<const Triangle> triangles);

}  // namespace cohort
