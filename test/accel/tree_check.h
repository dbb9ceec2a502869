// Structural invariants of a built KD-tree. Each function returns human-readable violations (the
// first few), empty when the tree is fine.
#pragma once

#include <string>
#include <vector>

#include "runtime/accel/kdtree/kdtree.h"

namespace cohort::test {

// Device layout: children in range and adjacent, breadth-first order (the k-th inner node has its
// children at 2k + 1 and 2k + 2, depths never decrease), every node but the root referenced exactly
// once, splits inside their cells, leaf lists in range, depth <= max_depth, stats consistent with
// the arrays (counts, depth and the SAH cost with the default costs, recomputed node by node), every
// kept triangle in at least one leaf.
std::vector<std::string> layout_errors(const KdTree& tree, int max_depth);

// Every triangle appears in every leaf whose cell interior it overlaps (cells shrunk by a relative
// 1e-4 on each axis with extent; along a flat axis only triangles lying in that plane count).
// Costs a descent per triangle: use on small trees.
std::vector<std::string> coverage_errors(const KdTree& tree);

// One line of stats for the test log.
std::string summary(const KdTree& tree);

// The kept triangles of `positions` (degenerate ones dropped, as every tree keeps them) in a
// KD-tree of one leaf: what the BVH builders take and brute force checks against.
KdTree kept_triangles(const std::vector<glm::vec3>& positions);

}  // namespace cohort::test
