// The recursive SAH build of Wald & Havran 2006 ("On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)"), the O(N log N) variant: the events are sorted once at the root and
// every node after that costs time linear in its size (kdtree_sah.cpp, kdtree_partition.cpp).
// Subtrees above kParallelTriangles are built as TBB tasks into their own pointer-free Subtree and
// appended in a fixed order, so the tree is the same bits whatever the thread timing.
#include <fmt/format.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
namespace {

// Below this a node's subtree is built serially: a task would cost more than it saves.
constexpr std::size_t kParallelTriangles = 4096;

// Wald & Havran's "bad refines" guard: a split after which both children still hold every triangle
// makes no progress; after this many in a row the node becomes a leaf. With the strict
// "split only when C_best <= K_I N" rule such a split cannot win (P_L + P_R > 1), so this is a
// second line of defence for the degenerate inputs (copies of one triangle, coplanar sheets) in
// case the cost rule is ever relaxed.
constexpr int kMaxBadRefines = 3;

class Builder {
 public:
  Builder(std::span<const Triangle> triangles, const KdBuildOptions& options, int max_depth)
      : triangles_(triangles), options_(options), max_depth_(max_depth) {}

  // Builds the subtree of `work` into `out`; returns the index of its root there.
  std::uint32_t build(Subtree& out, NodeWork work, int depth, int bad_refines) const;

 private:
  bool must_be_leaf(const NodeWork& work, int depth) const;
  static std::uint32_t make_leaf(Subtree& out, const NodeWork& work);
  static std::uint32_t append(Subtree& out, const Subtree& child);

  std::span<const Triangle> triangles_;
  const KdBuildOptions& options_;
  int max_depth_;
};

// The intermediate tree uses 32-bit offsets like the device layout; kdtree_layout.cpp checks the
// tighter 30-bit limits, this only keeps the offsets from wrapping before it gets there.
std::uint32_t checked_offset(std::size_t value) {
  if (value > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error(
        fmt::format("KD-tree has {} leaf references or nodes; at most 2^32 fit", value));
  }
  return static_cast<std::uint32_t>(value);
}

bool Builder::must_be_leaf(const NodeWork& work, int depth) const {
  const auto leaf_size = static_cast<std::size_t>(std::max(options_.leaf_triangles, 0));
  return work.tris.size() <= leaf_size || depth >= max_depth_;
}

std::uint32_t Builder::make_leaf(Subtree& out, const NodeWork& work) {
  const std::uint32_t index = checked_offset(out.nodes.size());
  checked_offset(out.leaf_triangles.size() + work.tris.size());
  out.nodes.push_back({KD_LEAF, 0.f, static_cast<std::uint32_t>(out.leaf_triangles.size()),
                       static_cast<std::uint32_t>(work.tris.size())});
  out.leaf_triangles.insert(out.leaf_triangles.end(), work.tris.begin(), work.tris.end());
  return index;
}

// Appends a subtree built on its own, shifting its node and leaf-list indices.
std::uint32_t Builder::append(Subtree& out, const Subtree& child) {
  checked_offset(out.nodes.size() + child.nodes.size());
  checked_offset(out.leaf_triangles.size() + child.leaf_triangles.size());
  const auto node_offset = static_cast<std::uint32_t>(out.nodes.size());
  const auto leaf_offset = static_cast<std::uint32_t>(out.leaf_triangles.size());
  for (BuildNode node : child.nodes) {
    if (node.axis == KD_LEAF) {
      node.a += leaf_offset;
    } else {
      node.a += node_offset;
      node.b += node_offset;
    }
    out.nodes.push_back(node);
  }
  out.leaf_triangles.insert(out.leaf_triangles.end(), child.leaf_triangles.begin(),
                            child.leaf_triangles.end());
  return node_offset;
}

std::uint32_t Builder::build(Subtree& out, NodeWork work, int depth, int bad_refines) const {
  if (must_be_leaf(work, depth)) return make_leaf(out, work);
  const std::size_t count = work.tris.size();
  const bool parallel = options_.parallel && count >= kParallelTriangles;
  const SplitPlane plane = find_best_plane(work, options_, parallel);
  // Wald & Havran's termination criterion: split only when the best plane beats the leaf, K_I N.
  if (!plane.valid() || !(plane.cost <= options_.intersection_cost * static_cast<float>(count))) {
    return make_leaf(out, work);
  }
  const bool no_progress = plane.left_count == count && plane.right_count == count;
  bad_refines = no_progress ? bad_refines + 1 : 0;
  if (bad_refines >= kMaxBadRefines) return make_leaf(out, work);

  std::array<NodeWork, 2> children = partition(std::move(work), plane, triangles_, parallel);
  const std::uint32_t index = checked_offset(out.nodes.size());
  out.nodes.push_back({static_cast<std::uint32_t>(plane.axis), plane.pos, 0, 0});
  std::uint32_t left = 0, right = 0;
  if (parallel) {
    Subtree left_tree, right_tree;
    tbb::parallel_invoke(
        [&] { build(left_tree, std::move(children[0]), depth + 1, bad_refines); },
        [&] { build(right_tree, std::move(children[1]), depth + 1, bad_refines); });
    left = append(out, left_tree);
    right = append(out, right_tree);
  } else {
    left = build(out, std::move(children[0]), depth + 1, bad_refines);
    right = build(out, std::move(children[1]), depth + 1, bad_refines);
  }
  out.nodes[index].a = left;  // re-indexed: the recursion grew the vector
  out.nodes[index].b = right;
  return index;
}

// The root: every kept triangle with its own bounds, events sorted once (the only full sort).
NodeWork root_work(std::span<const Triangle> triangles, const Bounds& bounds, bool parallel) {
  NodeWork work;
  work.voxel = bounds;
  work.tris.resize(triangles.size());
  std::iota(work.tris.begin(), work.tris.end(), 0u);
  for (auto& list : work.events) list.reserve(2 * triangles.size());
  for (std::uint32_t i = 0; i < triangles.size(); ++i) {
    Bounds box;
    box.extend(vertex(triangles[i].v0));
    box.extend(vertex(triangles[i].v1));
    box.extend(vertex(triangles[i].v2));
    push_events(work.events, box, i);
  }
  auto sort = [&](int axis) {
    auto& list = work.events[axis];
    if (parallel) {
      tbb::parallel_sort(list.begin(), list.end());  // a total order: same result as std::sort
    } else {
      std::sort(list.begin(), list.end());
    }
  };
  for (int axis = 0; axis < 3; ++axis) sort(axis);
  return work;
}

}  // namespace

int effective_max_depth(const KdBuildOptions& options, std::size_t triangle_count) {
  int depth = options.max_depth;
  if (depth <= 0) {
    const double n = static_cast<double>(std::max<std::size_t>(triangle_count, 1));
    depth = static_cast<int>(std::lround(8.0 + 1.8 * std::log2(n)));
  }
  return std::clamp(depth, 0, kDepthCap);
}

Subtree build_subtree(std::span<const Triangle> triangles, const Bounds& bounds,
                      const KdBuildOptions& options) {
  Subtree out;
  const int max_depth = effective_max_depth(options, triangles.size());
  const Builder builder(triangles, options, max_depth);
  builder.build(out, root_work(triangles, bounds, options.parallel), 0, 0);
  return out;
}

}  // namespace cohort::kd
