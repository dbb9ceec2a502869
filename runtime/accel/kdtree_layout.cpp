// Flattening the intermediate tree into the device layout of kernels/common/types.h: breadth-first
// node order with the two children of every inner node adjacent, so one index names both and the
// top L levels are a prefix of the array (what a kernel caching the top of the tree needs).
#include <fmt/format.h>

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
  tree.nodes.clear();
  tree.leaf_triangles.clear();
  const auto [node_count, leaf_entries] = sizes(subtree);
  tree.nodes.reserve(node_count);
  tree.leaf_triangles.reserve(leaf_entries);
  // `order` is the breadth-first queue and, by position, the output index of every node: the two
  // children of a node are queued together, so they land next to each other. Entries name their
  // subtree by an index into `trees` (8 bytes an entry: the queue holds every node).
  struct Entry {
    std::uint32_t tree;
    std::uint32_t node;
  };
  std::vector<const Subtree*> trees{&subtree};
  std::vector<Entry> order;
  order.reserve(node_count);
  order.push_back({0, 0});
  auto queue = [&](std::uint32_t parent, std::uint32_t child) {
    if (child & kSpawnedBit) {
      const Subtree* spawned = &trees[parent]->spawned[child & ~kSpawnedBit];
      trees.push_back(spawned);
      order.push_back({static_cast<std::uint32_t>(trees.size() - 1), 0});
    } else {
      order.push_back({parent, child});
    }
  };
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto [tree_index, index] = order[i];
    const Subtree* in = trees[tree_index];
    const BuildNode& node = in->nodes[index];
    if (node.axis == KD_LEAF) {
      tree.nodes.push_back(leaf_node(node.b, tree.leaf_triangles.size()));
      const auto first = in->leaf_triangles.begin() + node.a;
      tree.leaf_triangles.insert(tree.leaf_triangles.end(), first, first + node.b);
    } else {
      tree.nodes.push_back(inner_node(node, order.size()));
      queue(tree_index, node.a);
      queue(tree_index, node.b);
    }
  }
}

}  // namespace cohort::kd
