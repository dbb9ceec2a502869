// Internals of the KD-tree build shared by kdtree_builder.cpp, kdtree_sah.cpp,
// kdtree_partition.cpp, kdtree_layout.cpp and kdtree_stats.cpp. Not part of the public contract.
//
// The build follows Wald & Havran, "On building fast kd-trees for ray tracing, and on doing that
// in O(N log N)" (IEEE RT 2006): every node owns one event list per axis, sorted once at the root;
// the SAH sweep, the left/right/both classification and the splitting of the lists are linear in
// the node size, and only the events of clipped straddling triangles are sorted again.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "kernels/common/kdtree_traverse.h"
#include "runtime/accel/kdtree.h"
#include "runtime/scene/bounds.h"

namespace cohort::kd {

// ---- Events ------------------------------------------------------------------------------------
// Wald & Havran's event types. Their order (end < planar < start at the same position) is what
// lets one sweep count N_L, N_P and N_R for every candidate plane (their incremental sweep).
enum EventType : std::uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

constexpr std::uint32_t kLocalBits = 30;
constexpr std::uint32_t kLocalMask = (1u << kLocalBits) - 1u;

// 8 bytes: position, and the type above the node-local triangle index. Comparing `code` after
// `pos` sorts by (position, type, triangle), a total order, so every sort is deterministic.
struct Event {
  float pos;
  std::uint32_t code;

  static Event make(float pos, EventType type, std::uint32_t local) {
    return {pos + 0.0f, (static_cast<std::uint32_t>(type) << kLocalBits) | local};  // -0 -> +0
  }
  EventType type() const { return static_cast<EventType>(code >> kLocalBits); }
  std::uint32_t local() const { return code & kLocalMask; }
  friend bool operator<(const Event& a, const Event& b) {
    return a.pos < b.pos || (a.pos == b.pos && a.code < b.code);
  }
};

using EventLists = std::array<std::vector<Event>, 3>;

// The work of one node: its cell, its triangles and their (clipped) extents as events. Triangles
// are named by a node-local index (their position in `tris`), so side flags and index maps are
// node-local arrays and sibling subtrees can be built on different threads without sharing state.
struct NodeWork {
  Bounds voxel;
  std::vector<std::uint32_t> tris;  // kept-triangle indices, ascending
  EventLists events;                // per axis, sorted
};

// Appends the events of one triangle whose extent (inside the cell) is `box`.
void push_events(EventLists& lists, const Bounds& box, std::uint32_t local);

// ---- SAH ---------------------------------------------------------------------------------------
struct SplitPlane {
  int axis = -1;  // -1: no candidate
  float pos = 0.f;
  bool planar_left = true;  // where triangles lying in the plane go
  float cost = 0.f;
  std::uint32_t left_count = 0;  // triangles on each side, before clipping
  std::uint32_t right_count = 0;
  bool valid() const { return axis >= 0; }
};

// The best plane of the sweep over all three event lists (Wald & Havran's FindPlane).
SplitPlane find_best_plane(const NodeWork& work, const KdBuildOptions& options, bool parallel);

// Splits the node's triangles and event lists along `plane` in linear time, clipping straddling
// triangles to each child cell (Wald & Havran's perfect splits). Consumes `work`.
std::array<NodeWork, 2> partition(NodeWork work, const SplitPlane& plane,
                                  std::span<const Triangle> triangles, bool parallel);

// ---- Intermediate tree -------------------------------------------------------------------------
// Pointer-free, so a subtree built on another thread is a plain value that the parent appends in a
// fixed order: the result is the same bits whatever the thread timing.
struct BuildNode {
  std::uint32_t axis = KD_LEAF;  // 0..2, or KD_LEAF
  float split = 0.f;
  std::uint32_t a = 0;  // inner: left child index; leaf: first entry in Subtree::leaf_triangles
  std::uint32_t b = 0;  // inner: right child index; leaf: triangle count
};

struct Subtree {
  std::vector<BuildNode> nodes;  // nodes[0] is the root
  std::vector<std::uint32_t> leaf_triangles;
};

// The recursive SAH build over the kept triangles (kdtree_builder.cpp).
Subtree build_subtree(std::span<const Triangle> triangles, const Bounds& bounds,
                      const KdBuildOptions& options);

// Deepest leaf the builder makes (root = depth 0). The traversal pushes at most one stack entry per
// inner node on the path, so depth KD_MAX_DEPTH would just fit its 48-entry stack; the margin keeps
// room for traversal variants that push one more entry (a restart point, the PTH subtree root).
constexpr int kDepthCap = KD_MAX_DEPTH - 4;

// The depth limit actually used: options.max_depth, or 8 + 1.8 log2(N), capped (see kDepthCap). The
// factor was 1.3 until GPU runs showed the limit binding: on the H100, 1.8 gave 1.8x the diffuse
// rays/s of the armadillo and the Sponza interior (docs/results.md); 2.0 to 3.0 gained nothing more.
int effective_max_depth(const KdBuildOptions& options, std::size_t triangle_count);

// Breadth-first device layout (kdtree_layout.cpp). Throws std::length_error when an index does
// not fit the 30 bits of KdNode::word0.
void flatten(const Subtree& subtree, KdTree& tree);

// Fills tree.stats from the flattened tree, except dropped_triangles and build_seconds.
void compute_stats(KdTree& tree, const KdBuildOptions& options);

inline glm::vec3 vertex(const co_float4& v) { return {v.x, v.y, v.z}; }

}  // namespace cohort::kd
