// Flattening the intermediate tree into the device layout of kernels/common/types.h: breadth-first
// node order with the two children of every inner node adjacent, so one index names both and the
// top L levels are a prefix of the array (what a kernel caching the top of the tree needs).
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
namespace {

void check_fits(std::size_t value, std::size_t limit, const char* what) {
  if (value > limit) {
    throw std::length_error(fmt::format(
        "KD-tree too large for the device layout: {} is {}, the 8-byte KdNode holds at most {}",
        what, value, limit));
  }
}

KdNode inner_node(const BuildNode& node, std::size_t left_child) {
  check_fits(left_child + 1, KD_MAX_INDEX, "a child node index");
  std::uint32_t split_bits = 0;
  std::memcpy(&split_bits, &node.split, sizeof split_bits);
  return {static_cast<std::uint32_t>(left_child) << 2 | node.axis, split_bits};
}

KdNode leaf_node(std::size_t count, std::size_t first) {
  check_fits(count, KD_MAX_INDEX, "a leaf's triangle count");
  check_fits(first + count, std::numeric_limits<std::uint32_t>::max(), "the leaf list length");
  return {static_cast<std::uint32_t>(count) << 2 | KD_LEAF, static_cast<std::uint32_t>(first)};
}

// Nodes and leaf entries of a subtree and those it spawned.
std::array<std::size_t, 2> sizes(const Subtree& subtree) {
  std::array<std::size_t, 2> total{subtree.nodes.size(), subtree.leaf_triangles.size()};
  for (const Subtree& child : subtree.spawned) {
    const auto [nodes, leaf_triangles] = sizes(child);
    total[0] += nodes;
    total[1] += leaf_triangles;
  }
  return total;
}

}  // namespace

void flatten(const Subtree& subtree, KdTree& tree) {
  const auto [node_count, leaf_entries] = sizes(subtree);
  tree.nodes.assign(node_count, KdNode{});
  tree.leaf_triangles.assign(leaf_entries, 0u);
  // One level of the breadth-first order at a time: a level is the children of the previous one's
  // inner nodes in order, two each, so prefix counts of inner nodes and leaf entries over the level
  // give every node its output index, its children's and its leaf list's offset. Only the prefix
  // sums are serial (sequential passes over two arrays); reading the nodes, writing them and
  // copying leaf lists run in parallel over the level. The same layout as a breadth-first queue.
  struct Entry {
    const Subtree* tree;
    std::uint32_t node;
  };
  std::vector<Entry> level{{&subtree, 0}}, next;
  std::vector<std::size_t> inner_before, leaf_before;
  std::vector<BuildNode> level_nodes;  // the level's nodes, read once from their subtrees
  std::size_t level_first = 0, leaf_first = 0;
  constexpr std::size_t kGrain = 4096;
  while (!level.empty()) {
    const std::size_t n = level.size();
    inner_before.resize(n + 1);
    leaf_before.resize(n + 1);
    level_nodes.resize(n);
    // What each node adds (read in parallel: the nodes are scattered), then the prefix sums.
    inner_before[0] = leaf_before[0] = 0;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const BuildNode& node = level_nodes[i] = level[i].tree->nodes[level[i].node];
        const bool leaf = node.axis == KD_LEAF;
        inner_before[i + 1] = !leaf;
        leaf_before[i + 1] = leaf ? node.b : 0;
      }
    });
    for (std::size_t i = 0; i < n; ++i) {
      inner_before[i + 1] += inner_before[i];
      leaf_before[i + 1] += leaf_before[i];
    }
    const std::size_t children_first = level_first + n;
    if (inner_before[n] > 0) check_fits(children_first + 2 * inner_before[n], KD_MAX_INDEX, "a child node index");
    next.resize(2 * inner_before[n]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const Subtree* in = level[i].tree;
        const BuildNode& node = level_nodes[i];
        if (node.axis == KD_LEAF) {
          const std::size_t first = leaf_first + leaf_before[i];
          tree.nodes[level_first + i] = leaf_node(node.b, first);
          const auto from = in->leaf_triangles.begin() + node.a;
          std::copy(from, from + node.b, tree.leaf_triangles.begin() + static_cast<std::ptrdiff_t>(first));
          continue;
        }
        const std::size_t child = 2 * inner_before[i];
        tree.nodes[level_first + i] = inner_node(node, children_first + child);
        for (std::uint32_t c = 0; c < 2; ++c) {
          const std::uint32_t index = c == 0 ? node.a : node.b;
          next[child + c] = (index & kSpawnedBit) ? Entry{&in->spawned[index & ~kSpawnedBit], 0}
                                                  : Entry{in, index};
        }
      }
    });
    level_first = children_first;
    leaf_first += leaf_before[n];
    level.swap(next);
  }
}

}  // namespace cohort::kd
