#include "accel/tree_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>
#include <utility>

#include "kernels/common/accel/kdtree_traverse.h"
#include "runtime/accel/clip.h"

namespace cohort::test {
namespace {

constexpr std::size_t kMaxErrors = 10;

struct Errors {
  std::vector<std::string> list;
  template <typename... Args>
  void add(fmt::format_string<Args...> format, Args&&... args) {
    if (list.size() < kMaxErrors) list.push_back(fmt::format(format, std::forward<Args>(args)...));
  }
};

std::array<Bounds, 2> child_cells(const Bounds& cell, KdNode node) {
  std::array<Bounds, 2> cells{cell, cell};
  cells[0].hi[kd_axis(node)] = co_as_float(node.word1);
  cells[1].lo[kd_axis(node)] = co_as_float(node.word1);
  return cells;
}

glm::vec3 vertex(const co_float4& v) { return {v.x, v.y, v.z}; }

void check_inner(const KdTree& tree, std::size_t i, std::size_t inner_rank, const Bounds& cell,
                 std::vector<int>& references, Errors& errors) {
  const KdNode node = tree.nodes[i];
  const std::size_t child = kd_left_child(node);
  if (child != 2 * inner_rank + 1)
    errors.add("node {}: children at {}, breadth-first needs {}", i, child, 2 * inner_rank + 1);
  if (child <= i || child + 1 >= tree.nodes.size()) {
    errors.add("node {}: child index {} out of range", i, child);
    return;
  }
  ++references[child];
  ++references[child + 1];
  const float split = co_as_float(node.word1);
  const int axis = static_cast<int>(kd_axis(node));
  if (!(split >= cell.lo[axis] && split <= cell.hi[axis])) {
    errors.add("node {}: split {} outside its cell [{}, {}]", i, split, cell.lo[axis],
               cell.hi[axis]);
  }
}

void check_leaf(const KdTree& tree, std::size_t i, std::vector<bool>& seen, Errors& errors) {
  const KdNode node = tree.nodes[i];
  const std::size_t first = kd_leaf_first(node), count = kd_leaf_count(node);
  if (first + count > tree.leaf_triangles.size()) {
    errors.add("leaf {}: list [{}, {}) past the end", i, first, first + count);
    return;
  }
  std::vector<std::uint32_t> list(tree.leaf_triangles.begin() + first,
                                  tree.leaf_triangles.begin() + first + count);
  std::sort(list.begin(), list.end());
  if (std::adjacent_find(list.begin(), list.end()) != list.end())
    errors.add("leaf {}: duplicate entry", i);
  for (std::uint32_t tri : list) {
    if (tri >= tree.triangles.size())
      errors.add("leaf {}: triangle {} out of range", i, tri);
    else
      seen[tri] = true;
  }
}

// The SAH cost of the flattened tree with the default costs, node by node (the builder sums it
// as it goes; this is the independent figure it must match).
double layout_sah(const KdTree& tree, const std::vector<Bounds>& cell) {
  const KdBuildOptions costs;
  auto area = [](const Bounds& b) {
    const glm::dvec3 e = glm::dvec3(b.hi) - glm::dvec3(b.lo);
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
  };
  const double root = tree.bounds.empty() ? 0.0 : area(tree.bounds);
  double sah = 0;
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode node = tree.nodes[i];
    const double cost = kd_is_leaf(node) ? costs.intersection_cost * kd_leaf_count(node) : costs.traversal_cost;
    sah += (root > 0.0 ? area(cell[i]) / root : 1.0) * cost;
  }
  return sah;
}

void check_stats(const KdTree& tree, std::size_t leaves, std::size_t empty_leaves,
                 std::size_t references, int depth, double sah, Errors& errors) {
  const KdTreeStats& s = tree.stats;
  if (s.empty_leaf_count != empty_leaves)
    errors.add("stats.empty_leaf_count {} != {}", s.empty_leaf_count, empty_leaves);
  if (!(std::abs(s.sah_cost - sah) <= 1e-9 * std::max(1.0, sah)))
    errors.add("stats.sah_cost {} != {} (default costs)", s.sah_cost, sah);
  if (s.node_count != tree.nodes.size())
    errors.add("stats.node_count {} != {}", s.node_count, tree.nodes.size());
  if (s.leaf_count != leaves) errors.add("stats.leaf_count {} != {}", s.leaf_count, leaves);
  if (s.leaf_references != references)
    errors.add("stats.leaf_references {} != {}", s.leaf_references, references);
  if (references != tree.leaf_triangles.size())
    errors.add("leaf lists hold {} entries, leaves use {}", tree.leaf_triangles.size(), references);
  if (s.depth != depth) errors.add("stats.depth {} != {}", s.depth, depth);
}

// The interior a triangle must be registered in when it overlaps it: the cell shrunk on each axis
// with extent by a relative 1e-4 (and at least a few float ulps of the coordinates, or touching a
// face within rounding would count); nullopt when that leaves nothing.
std::optional<Bounds> interior(const Bounds& cell) {
  Bounds inner = cell;
  for (int axis = 0; axis < 3; ++axis) {
    const float extent = cell.hi[axis] - cell.lo[axis];
    if (extent == 0.f) continue;
    const float scale = std::max(std::abs(cell.lo[axis]), std::abs(cell.hi[axis]));
    const float margin = std::max(1e-4f * extent, 1e-6f * scale);
    inner.lo[axis] += margin;
    inner.hi[axis] -= margin;
    if (!(inner.lo[axis] < inner.hi[axis])) return std::nullopt;
  }
  return inner;
}

bool must_contain(const Triangle& t, const Bounds& cell) {
  for (int axis = 0; axis < 3; ++axis) {
    if (cell.lo[axis] != cell.hi[axis]) continue;
    const float p = cell.lo[axis];
    if (vertex(t.v0)[axis] != p || vertex(t.v1)[axis] != p || vertex(t.v2)[axis] != p) return false;
  }
  const std::optional<Bounds> inner = interior(cell);
  return inner &&
         !kd::clip_triangle_bounds(vertex(t.v0), vertex(t.v1), vertex(t.v2), *inner).empty();
}

void check_coverage(const KdTree& tree, std::uint32_t tri, Errors& errors) {
  const Triangle& t = tree.triangles[tri];
  std::vector<std::pair<std::uint32_t, Bounds>> stack{{0u, tree.bounds}};
  while (!stack.empty()) {
    const auto [index, cell] = stack.back();
    stack.pop_back();
    const KdNode node = tree.nodes[index];
    if (!kd_is_leaf(node)) {
      const std::array<Bounds, 2> cells = child_cells(cell, node);
      for (std::uint32_t c = 0; c < 2; ++c) {
        if (!kd::clip_triangle_bounds(vertex(t.v0), vertex(t.v1), vertex(t.v2), cells[c]).empty()) {
          stack.push_back({kd_left_child(node) + c, cells[c]});
        }
      }
      continue;
    }
    if (!must_contain(t, cell)) continue;
    const auto first = tree.leaf_triangles.begin() + kd_leaf_first(node);
    if (std::find(first, first + kd_leaf_count(node), tri) == first + kd_leaf_count(node)) {
      errors.add("triangle {} overlaps leaf {} but is not in it", tri, index);
    }
  }
}

}  // namespace

std::vector<std::string> layout_errors(const KdTree& tree, int max_depth) {
  Errors errors;
  if (tree.nodes.empty()) return {"no nodes"};
  std::vector<int> references(tree.nodes.size(), 0), depth(tree.nodes.size(), 0);
  std::vector<Bounds> cell(tree.nodes.size());
  std::vector<bool> seen(tree.triangles.size(), false);
  cell[0] = tree.bounds;
  std::size_t inner_rank = 0, leaves = 0, empty_leaves = 0, refs = 0;
  int deepest = 0;
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode node = tree.nodes[i];
    if (i > 0 && depth[i] < depth[i - 1])
      errors.add("node {}: depth {} after depth {}", i, depth[i], depth[i - 1]);
    if (kd_is_leaf(node)) {
      // The leaf lists follow one another in node order, with no gap (the layout's contract).
      if (kd_leaf_first(node) != refs)
        errors.add("leaf {}: list at {}, after the lists before it at {}", i, kd_leaf_first(node), refs);
      ++leaves;
      empty_leaves += kd_leaf_count(node) == 0;
      refs += kd_leaf_count(node);
      deepest = std::max(deepest, depth[i]);
      check_leaf(tree, i, seen, errors);
      continue;
    }
    check_inner(tree, i, inner_rank++, cell[i], references, errors);
    const std::size_t child = kd_left_child(node);
    if (child + 1 >= tree.nodes.size()) continue;
    const std::array<Bounds, 2> cells = child_cells(cell[i], node);
    for (std::size_t c = 0; c < 2; ++c) {
      cell[child + c] = cells[c];
      depth[child + c] = depth[i] + 1;
    }
  }
  for (std::size_t i = 1; i < tree.nodes.size(); ++i) {
    if (references[i] != 1) errors.add("node {} referenced {} times", i, references[i]);
  }
  if (refs != tree.leaf_triangles.size())
    errors.add("leaf lists hold {} entries, the leaves {}", tree.leaf_triangles.size(), refs);
  if (deepest > max_depth || deepest > KD_MAX_DEPTH)
    errors.add("depth {} over the limit {}", deepest, max_depth);
  for (std::size_t tri = 0; tri < seen.size(); ++tri) {
    if (!seen[tri]) errors.add("triangle {} is in no leaf", tri);
  }
  check_stats(tree, leaves, empty_leaves, refs, deepest, layout_sah(tree, cell), errors);
  return errors.list;
}

std::vector<std::string> coverage_errors(const KdTree& tree) {
  Errors errors;
  for (std::uint32_t tri = 0; tri < tree.triangles.size(); ++tri) check_coverage(tree, tri, errors);
  return errors.list;
}

std::string summary(const KdTree& tree) {
  const KdTreeStats& s = tree.stats;
  return fmt::format(
      "{} tris ({} dropped): build {:.3f} s, depth {}, {} nodes, {} leaves ({} empty), "
      "{} refs ({:.2f}/tri), avg leaf {:.2f} tris, SAH cost {:.2f}, {:.1f} MiB",
      tree.triangles.size(), s.dropped_triangles, s.build_seconds, s.depth, s.node_count,
      s.leaf_count, s.empty_leaf_count, s.leaf_references,
      tree.triangles.empty() ? 0.0 : double(s.leaf_references) / double(tree.triangles.size()),
      s.average_leaf_triangles, s.sah_cost, double(s.bytes) / (1 << 20));
}

KdTree kept_triangles(const std::vector<glm::vec3>& positions) {
  KdBuildOptions one_leaf;
  one_leaf.leaf_triangles = INT_MAX;
  return build_kdtree(positions, one_leaf);
}

}  // namespace cohort::test
