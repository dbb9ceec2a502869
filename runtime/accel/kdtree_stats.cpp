// Statistics of a flattened KD-tree. The SAH cost is the expected cost of a random ray that meets
// the root box (MacDonald & Booth 1990): every node is reached with probability area(node) /
// area(root), an inner node costs K_T and a leaf K_I per triangle.
#include <tbb/parallel_for.h>

#include <algorithm>

#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
namespace {

constexpr std::size_t kStatsChunk = 16384;  // nodes per task and per partial sum

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
  // Breadth-first order: each level is the children of the previous level's inner nodes, in order,
  // so one level at a time carries the boxes down. A level's nodes are read in parallel in chunks
  // of fixed size whose partial sums are added in chunk order: the same figures for any thread
  // count (summed per chunk, so the SAH cost may differ in its last bits from a node-by-node sum).
  const double root_area = tree.bounds.empty() ? 0.0 : area(tree.bounds);
  struct Partial {
    double sah = 0;
    std::size_t leaves = 0, empty = 0, references = 0, inner = 0;
  };
  std::vector<Bounds> level_box, next_box;
  if (!tree.nodes.empty()) level_box.push_back(tree.bounds);
  std::size_t first = 0;
  for (int depth = 0; !level_box.empty(); ++depth) {
    const std::size_t n = level_box.size();
    const std::size_t children_first = first + n;
    const std::size_t chunks = (n + kStatsChunk - 1) / kStatsChunk;
    std::vector<Partial> partial(chunks);
    // The next level holds two children per inner node of this one: at most 2n.
    next_box.resize(2 * n);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
      Partial& p = partial[k];
      for (std::size_t i = k * kStatsChunk; i < std::min(n, (k + 1) * kStatsChunk); ++i) {
        const KdNode node = tree.nodes[first + i];
        const double weight = root_area > 0.0 ? area(level_box[i]) / root_area : 1.0;
        if (kd_is_leaf(node)) {
          const std::uint32_t count = kd_leaf_count(node);
          ++p.leaves;
          p.empty += count == 0;
          p.references += count;
          p.sah += weight * options.intersection_cost * count;
          continue;
        }
        ++p.inner;
        p.sah += weight * options.traversal_cost;
        const std::array<Bounds, 2> children = split_box(level_box[i], node);
        const std::size_t left = kd_left_child(node) - children_first;
        next_box[left] = children[0];
        next_box[left + 1] = children[1];
      }
    });
    std::size_t inner = 0;
    for (const Partial& p : partial) {
      s.sah_cost += p.sah;
      s.leaf_count += p.leaves;
      s.empty_leaf_count += p.empty;
      s.leaf_references += p.references;
      inner += p.inner;
    }
    if (inner < n) s.depth = depth;  // this level has leaves
    next_box.resize(2 * inner);
    level_box.swap(next_box);
    first = children_first;
  }
  const std::size_t filled = s.leaf_count - s.empty_leaf_count;
  s.average_leaf_triangles = filled ? static_cast<double>(s.leaf_references) / filled : 0.0;
  s.bytes = tree.nodes.size() * sizeof(KdNode) +
            tree.leaf_triangles.size() * sizeof(std::uint32_t) +
            tree.triangles.size() * sizeof(Triangle);
}

}  // namespace cohort::kd
