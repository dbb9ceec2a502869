// A 4-wide BVH over the KD-tree's kept triangles, in the device layout of kernels/common/core/types.h
// (Bvh4Node): what renders trace with unless a KD-tree is asked for (--tree bvh4, and auto;
// kernels/common/accel/bvh4_traverse.h). Its leaves hold the same kept triangles as the KD-tree's, so
// every ray gets the same hit from either.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "kernels/common/core/types.h"

namespace cohort {

struct Bvh4Stats {
  std::size_t node_count = 0;   // 4-wide nodes
  std::size_t leaf_count = 0;
  std::size_t references = 0;   // leaf list entries: triangles, large ones split into several
  int depth = 0;                // deepest leaf; the root's children are at depth 1
  double average_leaf_triangles = 0;
  double sah_cost = 0;          // expected node visits + triangle tests of a random ray through the root
  double build_seconds = 0;
  std::size_t bytes = 0;        // nodes + the leaves' triangles (the device's copy)
};

struct Bvh4 {
  // Node 0 is the root; each node before its children. The top BVH4_TOP_LEVELS levels come first,
  // breadth first, the rest depth first (each subtree contiguous).
  std::vector<Bvh4Node> nodes;
  // top_level_starts[d]: the first node at depth d (the root's is 0) of the breadth-first top; the
  // last entry counts the top's nodes, so the nodes above depth d are a prefix of starts[d] nodes.
  std::vector<std::uint32_t> top_level_starts;
  // The leaves' entries (a leaf reference names its first entry and count): each a copy of a kept
  // triangle, with that triangle's index in v0.w (kernels/common/accel/bvh4_traverse.h).
  std::vector<Triangle> leaf_vertices;
  Bvh4Stats stats;
};

// Binned SAH over triangle centroids (Wald, "On fast construction of SAH-based bounding volume
// hierarchies", 2007), a binary tree collapsed into 4-wide nodes. The same tree for any thread
// count. Throws InputError when there are more triangles than a leaf reference can name.
Bvh4 build_bvh4(std::span<const Triangle> triangles);

}  // namespace cohort
