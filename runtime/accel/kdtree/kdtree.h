// SAH KD-tree over a triangle soup, in the device layout of kernels/common/core/types.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/common/core/types.h"
#include "runtime/scene/bounds.h"
#include "runtime/util/uninitialised_vector.h"

namespace cohort {

struct KdBuildOptions {
  float traversal_cost = 1.0f;     // cost of one inner-node step
  float intersection_cost = 1.5f;  // cost of one ray-triangle test
  float empty_bonus = 0.8f;        // SAH cost factor (1 - bonus) for splits that cut off empty space
  int max_depth = 0;               // 0: 8 + 1.8 log2(N), capped below KD_MAX_DEPTH
  int leaf_triangles = 1;          // never split a node with this many triangles or fewer
  // Termination. Default (compact false): split when the chosen plane beats a leaf with the
  // empty-space bonus counted (Wald & Havran): the deepest trees, fastest to trace on the H200.
  // compact: the bonus chooses among planes but does not decide whether to split:
  // a node splits only when some candidate plane beats a leaf (K_I N) by the plain SAH, and a node
  // of at most this many references only when the chosen plane itself does. With the bonus in the
  // test, cutting off any empty sliver beat a leaf (0.2 (K_T + K_I N) < K_I N), so nearly every
  // branch ran to the depth limit: on Crytek Sponza subdivided once this takes the tree from 11.0M
  // nodes to 5.8M and its SAH cost from 127.97 to 126.71 (results/raw/nvidia-h200-2026-12-02-f94839e; 8 here: 5.2M nodes, but
  // the armadillo's SAH 2.4% above the old build's). 0: the chosen plane's plain cost is never
  // required, only that some plane pays.
  // On the H200 the compact Sponza tree takes 0.74x the bytes and traces 2-5 % slower (results/raw/nvidia-h200-2026-12-03-4b25879):
  // the first step a memory budget takes (budget.cpp). On CPUs it traces as fast in 0.6x the
  // nodes, so a render whose devices are all CPUs builds it (tree_options, --tree).
  bool compact = false;
  int plain_sah_triangles = 6;
  // Nodes with more triangle references than this choose among `bins - 1` evenly spaced planes per
  // axis (linear time); smaller ones by the exact sweep over every triangle boundary (a sort).
  // INT_MAX: exact everywhere, the tree of Wald & Havran's O(N log N) build (slower). 128 rather
  // than 64: the exact nodes of 65-128 references build Sponza x4 and the bunny x16 0.95x as long
  // (an empty cut hands its candidates to the child without a search), SAH within 0.6 % either way
  // on 13 models (2026-12-04, results/raw/dev-2core-2026-12-04-7ce485a).
  int exact_triangles = 128;
  int bins = 512;
  bool parallel = true;            // build subtrees with TBB
};

struct KdTreeStats {
  int depth = 0;                   // deepest leaf (root = depth 0)
  std::size_t node_count = 0;
  std::size_t leaf_count = 0;
  std::size_t empty_leaf_count = 0;
  std::size_t leaf_references = 0;     // total triangle references in leaves
  double average_leaf_triangles = 0;   // over non-empty leaves
  double sah_cost = 0;                 // expected cost of a random ray, with the options' costs
  std::size_t dropped_triangles = 0;   // degenerate, zero-area, NaN or infinite
  double build_seconds = 0;
  std::size_t bytes = 0;               // nodes + leaf lists + triangles
  bool compact = false;                // built with KdBuildOptions::compact
};

// "compact" or "deep": the tree's kind as --tree, --stats and the bench JSON name it.
inline const char* tree_kind(const KdTreeStats& stats) { return stats.compact ? "compact" : "deep"; }

// The arrays are written in parallel right after sizing (UninitialisedVector: resize does not clear).
struct KdTree {
  UninitialisedVector<KdNode> nodes;        // breadth-first, children adjacent; node 0 is the root
  UninitialisedVector<std::uint32_t> leaf_triangles;  // leaf lists, entries index `triangles`
  UninitialisedVector<Triangle> triangles;  // kept triangles, in input order
  UninitialisedVector<std::uint32_t> source_index;  // input triangle index of each kept triangle
  Bounds bounds;                           // of the kept triangles
  KdTreeStats stats;
};

// positions: 3 per triangle. Bad triangles are dropped and counted, never an error; an input with
// no good triangle gives a tree with one empty leaf.
KdTree build_kdtree(std::span<const glm::vec3> positions, const KdBuildOptions& options = {});

// The same tree with the depth limit lowered as far as needed for stats.bytes (nodes, leaf lists,
// triangles) to fit `max_bytes`: the default tree when it fits. Throws InputError naming the size
// needed when even a single leaf does not fit. stats.build_seconds counts every build it took.
KdTree build_kdtree_within(std::span<const glm::vec3> positions, const KdBuildOptions& options,
                           std::size_t max_bytes);

}  // namespace cohort
