// The KD-tree build's intermediate tree (pointer-free subtrees, one per build task), its sums for the
// statistics, and the steps from triangles to the device tree: build_subtree (builder.cpp),
// flatten (layout.cpp), compute_stats (stats.cpp). Internal to runtime/accel/kdtree.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "kernels/common/accel/kdtree_traverse.h"
#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/scene/bounds.h"

namespace cohort::kd {

// Pointer-free, so a subtree built on another thread is a plain value that its parent keeps in a
// fixed slot: the result is the same bits whatever the thread timing.
// A node in 8 bytes, as the device's KdNode: the build writes, and lay_out reads, half what 16
// bytes took (a 32-byte node made the build of Sponza x4 1.06x slower). The build is depth-first,
// so an inner node's left child is the next node of its Subtree; `word` names the right child,
// or, with kSpawnedFlag, the first of the two consecutive Subtree::spawned slots that hold its
// children (each built by another task).
struct BuildNode {
  std::uint32_t word = KD_LEAF;  // bits 0-1: axis 0..2 or KD_LEAF; then a leaf's count, or
                                 // kSpawnedFlag (bit 2) and the index above it
  std::uint32_t payload = 0;     // inner: the split position's bits; leaf: its first entry in
                                 // Subtree::leaf_triangles

  static BuildNode leaf(std::uint32_t count, std::uint32_t first) {
    return {count << 2 | KD_LEAF, first};
  }
  static BuildNode inner(int axis, float split) {
    return {static_cast<std::uint32_t>(axis), std::bit_cast<std::uint32_t>(split)};
  }
  bool is_leaf() const { return (word & 3u) == KD_LEAF; }
  std::uint32_t axis() const { return word & 3u; }
  float split() const { return std::bit_cast<float>(payload); }
  std::uint32_t count() const { return word >> 2; }
  std::uint32_t first() const { return payload; }
  bool spawned() const { return (word & kSpawnedFlag) != 0; }
  std::uint32_t index() const { return word >> 3; }  // the right child, or the first slot
  void set_right(std::uint32_t right) { word = axis() | right << 3; }
  void set_spawned(std::uint32_t first_slot) { word = axis() | kSpawnedFlag | first_slot << 3; }

  static constexpr std::uint32_t kSpawnedFlag = 4u;
  static constexpr std::uint32_t kMaxIndex = (1u << 29) - 1u;  // nodes or slots in one Subtree
  static constexpr std::uint32_t kMaxCount = (1u << 30) - 1u;  // references in one leaf
};
static_assert(sizeof(BuildNode) == 8);

// In lay_out's walk, a pending child with this bit set is the root of
// Subtree::spawned[child & ~kSpawnedBit], else a node of the same Subtree.
constexpr std::uint32_t kSpawnedBit = 1u << 31;

// A cell's surface area in double precision, as the SAH statistics sum it.
inline double cell_area(const Bounds& box) {
  const glm::dvec3 e = glm::dvec3(box.hi) - glm::dvec3(box.lo);
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

// What the statistics need of the nodes, summed as the builder makes them (each node's cell is at
// hand there), so no pass over the finished tree is needed. Sums of cell areas, not yet divided by
// the root's: the SAH cost is (K_T inner_area + K_I leaf_reference_area) / area(root).
// Depths a node can have (root = 0); the builder stops below KD_MAX_DEPTH (kDepthCap).
constexpr std::size_t kLevels = KD_MAX_DEPTH;

struct SubtreeSums {
  double inner_area = 0;           // the cells of the inner nodes
  double leaf_reference_area = 0;  // each leaf's cell times its triangle count
  std::size_t inner = 0, leaves = 0, empty_leaves = 0, references = 0;
  int depth = 0;  // deepest leaf (root = depth 0)
  // Nodes and leaf-list entries per depth: where each level of the breadth-first layout starts,
  // and how far a subtree built by another task moves the nodes right of it (kdtree_layout.cpp).
  std::array<std::size_t, kLevels> level_nodes{}, level_leaf_entries{};

  void add_node(int at_depth, std::size_t leaf_entries) {
    ++level_nodes[static_cast<std::size_t>(at_depth)];
    level_leaf_entries[static_cast<std::size_t>(at_depth)] += leaf_entries;
  }
  void add(const SubtreeSums& other) {
    inner_area += other.inner_area;
    leaf_reference_area += other.leaf_reference_area;
    inner += other.inner;
    leaves += other.leaves;
    empty_leaves += other.empty_leaves;
    references += other.references;
    depth = std::max(depth, other.depth);
    for (std::size_t d = 0; d < kLevels; ++d) {
      level_nodes[d] += other.level_nodes[d];
      level_leaf_entries[d] += other.level_leaf_entries[d];
    }
  }
};

struct Subtree {
  std::vector<BuildNode> nodes;  // nodes[0] is the root
  std::vector<std::uint32_t> leaf_triangles;
  std::vector<Subtree> spawned;  // subtrees built in parallel, kept in place instead of copied
  SubtreeSums sums;              // of `nodes` only, not of `spawned`
};

// The subtree's sums and those of everything it spawned, in their fixed order (kdtree_stats.cpp).
SubtreeSums total_sums(const Subtree& subtree);

// The recursive SAH build over the kept triangles (kdtree_builder.cpp).
Subtree build_subtree(std::span<const Triangle> triangles, const Bounds& bounds,
                      const KdBuildOptions& options);

// Deepest leaf the builder makes (root = depth 0). The traversal pushes at most one stack entry per
// inner node on the path, so depth KD_MAX_DEPTH would just fit its 48-entry stack; the margin keeps
// room for traversal variants that push one more entry (a restart point, the PTH subtree root).
constexpr int kDepthCap = KD_MAX_DEPTH - 4;
static_assert(kDepthCap < static_cast<int>(kLevels));

// The depth limit actually used: options.max_depth, or 8 + 1.8 log2(N), capped (see kDepthCap). The
// factor was 1.3 until GPU runs showed the limit binding: on the H100, 1.8 gave 1.8x the diffuse
// rays/s of the armadillo and the Sponza interior (results/raw/pocl-2026-11-23-f393cc7); 2.0 to 3.0 gained nothing more.
int effective_max_depth(const KdBuildOptions& options, std::size_t triangle_count);

// Breadth-first device layout of the subtree and those it spawned (kdtree_layout.cpp), written by
// a depth-first walk. Throws std::length_error when an index does not fit the 30 bits of
// KdNode::word0.
void flatten(const Subtree& subtree, KdTree& tree);

// Fills tree.stats from the sums of the subtree and those it spawned (joined in their fixed
// order: the same figures for any thread count), except dropped_triangles and build_seconds.
void compute_stats(const Subtree& subtree, KdTree& tree, const KdBuildOptions& options);

}  // namespace cohort::kd
