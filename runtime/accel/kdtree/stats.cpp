// Statistics of a built KD-tree. The SAH cost is the expected cost of a random ray that meets
// the root box (MacDonald & Booth 1990): every node is reached with probability area(node) /
// area(root), an inner node costs K_T and a leaf K_I per triangle. The builder sums what this
// needs as it makes the nodes (Subtree::sums); this joins the sums. (A level-by-level pass over
// the finished tree took as long as a third of the build's own parallel time on 16 cores: it
// hardly ran faster with more threads.)
#include <algorithm>

#include "runtime/accel/kdtree/subtree.h"

namespace cohort::kd {
SubtreeSums total_sums(const Subtree& subtree) {
  SubtreeSums sums = subtree.sums;
  for (const Subtree& child : subtree.spawned) sums.add(total_sums(child));
  return sums;
}

void compute_stats(const Subtree& subtree, KdTree& tree, const KdBuildOptions& options) {
  const SubtreeSums sums = total_sums(subtree);
  KdTreeStats& s = tree.stats;
  s.node_count = tree.nodes.size();
  s.leaf_count = sums.leaves;
  s.empty_leaf_count = sums.empty_leaves;
  s.leaf_references = sums.references;
  s.depth = sums.depth;
  // Without a root area (no triangle kept) every node counts once, as a ray through a point would.
  const double root_area = tree.bounds.empty() ? 0.0 : cell_area(tree.bounds);
  s.sah_cost = root_area > 0.0
                   ? (options.traversal_cost * sums.inner_area +
                      options.intersection_cost * sums.leaf_reference_area) / root_area
                   : options.traversal_cost * static_cast<double>(sums.inner) +
                         options.intersection_cost * static_cast<double>(sums.references);
  const std::size_t filled = s.leaf_count - s.empty_leaf_count;
  s.average_leaf_triangles = filled ? static_cast<double>(s.leaf_references) / filled : 0.0;
  s.bytes = tree.nodes.size() * sizeof(KdNode) +
            tree.leaf_triangles.size() * sizeof(std::uint32_t) +
            tree.triangles.size() * sizeof(Triangle);
}

}  // namespace cohort::kd
