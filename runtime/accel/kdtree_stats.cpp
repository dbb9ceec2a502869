// Statistics of a flattened KD-tree. The SAH cost is the expected cost of a random ray that meets
// the root box (MacDonald & Booth 1990): every node is reached with probability area(node) /
// area(root), an inner node costs K_T and a leaf K_I per triangle.
#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
namespace {

double area(const Bounds& box) {
  const glm::dvec3 e = glm::dvec3(box.hi) - glm::dvec3(box.lo);
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

std::array<Bounds, 2> split_box(const Bounds& box, KdNode node) {
  std::array<Bounds, 2> children{box, box};
  const float split = co_as_float(node.word1);
  children[0].hi[kd_axis(node)] = split;
  children[1].lo[kd_axis(node)] = split;
  return children;
}

}  // namespace

void compute_stats(KdTree& tree, const KdBuildOptions& options) {
  KdTreeStats& s = tree.stats;
  s.depth = 0;
  s.node_count = tree.nodes.size();
  s.leaf_count = s.empty_leaf_count = s.leaf_references = 0;
  s.sah_cost = 0;
  // Breadth-first order puts every parent before its children: one forward pass carries the boxes.
  std::vector<Bounds> box(tree.nodes.size());
  std::vector<int> depth(tree.nodes.size(), 0);
  if (!tree.nodes.empty()) box[0] = tree.bounds;
  const double root_area = tree.bounds.empty() ? 0.0 : area(tree.bounds);
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode node = tree.nodes[i];
    const double weight = root_area > 0.0 ? area(box[i]) / root_area : 1.0;
    if (kd_is_leaf(node)) {
      const std::uint32_t count = kd_leaf_count(node);
      ++s.leaf_count;
      s.empty_leaf_count += count == 0;
      s.leaf_references += count;
      s.sah_cost += weight * options.intersection_cost * count;
      s.depth = std::max(s.depth, depth[i]);
      continue;
    }
    s.sah_cost += weight * options.traversal_cost;
    const std::array<Bounds, 2> children = split_box(box[i], node);
    for (std::uint32_t c = 0; c < 2; ++c) {
      box[kd_left_child(node) + c] = children[c];
      depth[kd_left_child(node) + c] = depth[i] + 1;
    }
  }
  const std::size_t filled = s.leaf_count - s.empty_leaf_count;
  s.average_leaf_triangles = filled ? static_cast<double>(s.leaf_references) / filled : 0.0;
  s.bytes = tree.nodes.size() * sizeof(KdNode) +
            tree.leaf_triangles.size() * sizeof(std::uint32_t) +
            tree.triangles.size() * sizeof(Triangle);
}

}  // namespace cohort::kd
