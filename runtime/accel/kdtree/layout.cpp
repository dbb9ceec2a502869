// Flattening the intermediate tree into the device layout of kernels/common/core/types.h: breadth-first
// node order with the two children of every inner node adjacent, so one index names both and the
// top L levels are a prefix of the array (what a kernel caching the top of the tree needs).
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "runtime/accel/kdtree/subtree.h"

namespace cohort::kd {
namespace {

void check_fits(std::size_t value, std::size_t limit, const char* what) {
  if (value > limit) {
    throw std::length_error(fmt::format(
        "KD-tree too large for the device layout: {} is {}, the 8-byte KdNode holds at most {}",
        what, value, limit));
  }
}

KdNode inner_node(std::uint32_t axis, float split, std::size_t left_child) {
  check_fits(left_child + 1, KD_MAX_INDEX, "a child node index");
  std::uint32_t split_bits = 0;
  std::memcpy(&split_bits, &split, sizeof split_bits);
  return {static_cast<std::uint32_t>(left_child) << 2 | axis, split_bits};
}

KdNode leaf_node(std::size_t count, std::size_t first) {
  check_fits(count, KD_MAX_INDEX, "a leaf's triangle count");
  check_fits(first + count, std::numeric_limits<std::uint32_t>::max(), "the leaf list length");
  return {static_cast<std::uint32_t>(count) << 2 | KD_LEAF, static_cast<std::uint32_t>(first)};
}

// Per depth, the next index of the breadth-first node array and of the leaf lists that a node
// or leaf list met there takes.
struct Cursor {
  std::array<std::size_t, kLevels> node{}, leaf{};
};

// Breadth-first order is, level by level, the left-to-right order of the nodes, and that is the
// order in which a depth-first walk (left child first) meets them. So walking the tree depth-first
// with a cursor per level puts each node where the level-by-level layout puts it: its index is the
// next of its level, its left child the next of the level below (met right after it), and its leaf
// list the next of its level's leaf lists. The walk reads each subtree's nodes in the order they
// were built (sequential, where a level-by-level pass jumps between subtrees); a spawned subtree
// is skipped by moving the cursors by its sizes per level and laid out by a task of its own from
// the cursors it was met with.
void lay_out(const Subtree& subtree, int root_depth, Cursor cursor, KdTree& tree) {
  struct Pending {
    std::uint32_t node;  // may carry kSpawnedBit
    int depth;
  };
  struct Spawned {
    const Subtree* subtree;
    int depth;
    Cursor cursor;
  };
  // A node's children are pushed right, then left: besides the two children of the last node,
  // at most one pending right child per level.
  std::array<Pending, kLevels + 2> stack;
  std::size_t top = 0;
  stack[top++] = {0, root_depth};
  std::vector<Spawned> spawned;
  KdNode* const nodes = tree.nodes.data();
  std::uint32_t* const lists = tree.leaf_triangles.data();
  while (top > 0) {
    const auto [index, depth] = stack[--top];
    const auto d = static_cast<std::size_t>(depth);
    if (index & kSpawnedBit) {
      const Subtree& child = subtree.spawned[index & ~kSpawnedBit];
      spawned.push_back({&child, depth, cursor});
      const SubtreeSums sizes = total_sums(child);
      for (std::size_t level = d; level < kLevels; ++level) {
        cursor.node[level] += sizes.level_nodes[level];
        cursor.leaf[level] += sizes.level_leaf_entries[level];
      }
      continue;
    }
    const BuildNode node = subtree.nodes[index];
    const std::size_t at = cursor.node[d]++;
    if (node.is_leaf()) {
      const std::size_t first = cursor.leaf[d];
      const std::uint32_t count = node.count();
      nodes[at] = leaf_node(count, first);
      const std::uint32_t* from = subtree.leaf_triangles.data() + node.first();
      for (std::uint32_t k = 0; k < count; ++k) lists[first + k] = from[k];  // about 3 entries
      cursor.leaf[d] += count;
      continue;
    }
    if (d + 1 >= kLevels) throw std::length_error("KD-tree deeper than the layout's levels");
    nodes[at] = inner_node(node.axis(), node.split(), cursor.node[d + 1]);
    const std::uint32_t left = node.spawned() ? kSpawnedBit | node.index() : index + 1;
    const std::uint32_t right = node.spawned() ? kSpawnedBit | (node.index() + 1) : node.index();
    stack[top++] = {right, depth + 1};
    stack[top++] = {left, depth + 1};
  }
  tbb::parallel_for(std::size_t{0}, spawned.size(), [&](std::size_t k) {
    lay_out(*spawned[k].subtree, spawned[k].depth, spawned[k].cursor, tree);
  });
}

}  // namespace

void flatten(const Subtree& subtree, KdTree& tree) {
  const SubtreeSums sizes = total_sums(subtree);
  Cursor first;  // where each level starts
  std::size_t node_count = 0, leaf_entries = 0;
  for (std::size_t level = 0; level < kLevels; ++level) {
    first.node[level] = node_count;
    first.leaf[level] = leaf_entries;
    node_count += sizes.level_nodes[level];
    leaf_entries += sizes.level_leaf_entries[level];
  }
  check_fits(node_count, KD_MAX_INDEX, "the node count");
  // Uninitialised (lay_out writes every node and list entry once, in parallel over subtrees).
  tree.nodes.resize(node_count);
  tree.leaf_triangles.resize(leaf_entries);
  lay_out(subtree, 0, first, tree);
}

}  // namespace cohort::kd
