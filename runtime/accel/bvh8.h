// A compressed 8-wide BVH (Ylitie, Karras & Laine, "Efficient Incoherent Ray Traversal on GPUs Through
// Compressed Wide BVHs", HPG 2017) over the KD-tree's kept triangles, in the device layout of
// kernels/common/core/types.h (Bvh8Node, 80 bytes): --tree bvh8, traced by
// kernels/common/accel/bvh8_traverse.h. Its leaves hold the same kept triangles as the other trees',
// so every ray gets the same hit from any of them.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/accel/bvh4.h"

namespace cohort {

// The same figures as the 4-wide BVH's (node_count counts 8-wide nodes; a leaf is a leaf child,
// at most BVH8_LEAF_MAX triangles).
using Bvh8Stats = Bvh4Stats;

struct Bvh8 {
  // Node 0 is the root. A node's inner children are consecutive (in slot order), each node's
  // children before their own children.
  std::vector<Bvh8Node> nodes;
  // The leaf children's triangles: each a copy of a kept triangle with that triangle's index in
  // v0.w; a node's leaf children's triangles are consecutive (in slot order).
  std::vector<Triangle> leaf_vertices;
  Bvh8Stats stats;
};

// The binary SAH tree of runtime/accel/binary_bvh.h (leaves of at most three references) collapsed
// into 8-wide nodes (the inner child of largest area opened until eight slots are full), the children
// placed in slots by the paper's octant assignment and their boxes quantised conservatively. The same
// tree for any thread count. Throws InputError for an empty input or one too large to index.
Bvh8 build_bvh8(std::span<const Triangle> triangles);

// The box of slot `slot` of `node` as the traversal decodes it (origin + q * 2^e, exact in float):
// lo x y z, then hi x y z. For the builder's tests.
std::array<float, 6> bvh8_child_box(const Bvh8Node& node, int slot);

}  // namespace cohort
