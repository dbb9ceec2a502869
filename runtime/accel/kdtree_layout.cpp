// Flattening the intermediate tree into the device layout of kernels/common/types.h: breadth-first
// node order with the two children of every inner node adjacent, so one index names both and the
// top L levels are a prefix of the array (what a kernel caching the top of the tree needs).
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>
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

// Working memory that grows as needed and is never cleared: every element a pass reads, the pass
// before it wrote (a std::vector would zero each level's new tail, serially).
template <typename T>
class GrowBuffer {
 public:
  T* get(std::size_t n) {
    if (n > capacity_) {
      capacity_ = std::max(n, 2 * capacity_);
      data_ = std::make_unique_for_overwrite<T[]>(capacity_);
    }
    return data_.get();
  }
  T* data() { return data_.get(); }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t capacity_ = 0;
};

}  // namespace

void flatten(const Subtree& subtree, KdTree& tree) {
  const auto [node_count, leaf_entries] = sizes(subtree);
  // Sizing clears the new memory, one thread per vector (hundreds of MB on a large scene): side by side.
  tbb::parallel_invoke([&] { tree.nodes.assign(node_count, KdNode{}); },
                       [&] { tree.leaf_triangles.assign(leaf_entries, 0u); });
  // One level of the breadth-first order at a time: a level is the children of the previous one's
  // inner nodes in order, two each, so counts of inner nodes and leaf entries before each node give
  // its output index, its children's and its leaf list's offset. The level is cut into chunks of a
  // fixed size: a first parallel pass reads the chunk's nodes and counts them, a short serial scan
  // over the chunks' counts gives each chunk's first offsets, and a second parallel pass writes the
  // chunk's nodes, leaf lists and the next level's entries, counting on from there. Nothing runs
  // over a whole level serially (a scan over every node did not scale past two cores), and the
  // working buffers grow without being cleared. The same layout as a breadth-first queue.
  struct Entry {
    const Subtree* tree;
    std::uint32_t node;
  };
  struct ChunkCounts {
    std::size_t inner = 0, leaf_entries = 0;
  };
  constexpr std::size_t kChunk = 4096;
  constexpr std::size_t kPrefetchAhead = 16;
  GrowBuffer<Entry> level, next;
  // The level's nodes, read once from their subtrees (BuildNode's fields without its initialisers,
  // so the buffer needs no clearing either).
  struct LevelNode {
    std::uint32_t axis;
    float split;
    std::uint32_t a, b;
  };
  GrowBuffer<LevelNode> level_nodes;
  std::vector<ChunkCounts> chunk_first;
  Entry* current = level.get(1);
  current[0] = {&subtree, 0};
  std::size_t n = 1, level_first = 0, leaf_first = 0;
  while (n > 0) {
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    LevelNode* nodes = level_nodes.get(n);
    chunk_first.assign(chunks + 1, ChunkCounts{});
    // What each chunk adds (read in parallel: the nodes are scattered over the subtrees).
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
      ChunkCounts counts;
      const std::size_t last = std::min(n, (k + 1) * kChunk);
      for (std::size_t i = k * kChunk; i < last; ++i) {
        // The nodes of a level lie far apart in memory (depth-first, as they were built): each
        // read is a cache miss, so the one kPrefetchAhead entries on is fetched early (and the
        // leaf lists likewise below).
        if (i + kPrefetchAhead < last) {
          const Entry& ahead = current[i + kPrefetchAhead];
          __builtin_prefetch(ahead.tree->nodes.data() + ahead.node);
        }
        const BuildNode& read = current[i].tree->nodes[current[i].node];
        const LevelNode& node = nodes[i] = {read.axis, read.split, read.a, read.b};
        if (node.axis == KD_LEAF) {
          counts.leaf_entries += node.b;
        } else {
          ++counts.inner;
        }
      }
      chunk_first[k + 1] = counts;
    });
    for (std::size_t k = 0; k < chunks; ++k) {
      chunk_first[k + 1].inner += chunk_first[k].inner;
      chunk_first[k + 1].leaf_entries += chunk_first[k].leaf_entries;
    }
    const std::size_t inner = chunk_first[chunks].inner;
    const std::size_t children_first = level_first + n;
    if (inner > 0) check_fits(children_first + 2 * inner, KD_MAX_INDEX, "a child node index");
    Entry* children = next.get(2 * inner);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
      std::size_t inner_before = chunk_first[k].inner;
      std::size_t leaf_before = leaf_first + chunk_first[k].leaf_entries;
      const std::size_t last = std::min(n, (k + 1) * kChunk);
      for (std::size_t i = k * kChunk; i < last; ++i) {
        if (i + kPrefetchAhead < last && nodes[i + kPrefetchAhead].axis == KD_LEAF) {
          const Entry& ahead = current[i + kPrefetchAhead];
          __builtin_prefetch(ahead.tree->leaf_triangles.data() + nodes[i + kPrefetchAhead].a);
        }
        const Subtree* in = current[i].tree;
        const LevelNode& node = nodes[i];
        if (node.axis == KD_LEAF) {
          tree.nodes[level_first + i] = leaf_node(node.b, leaf_before);
          const auto from = in->leaf_triangles.begin() + node.a;
          std::copy(from, from + node.b, tree.leaf_triangles.begin() + static_cast<std::ptrdiff_t>(leaf_before));
          leaf_before += node.b;
          continue;
        }
        const std::size_t child = 2 * inner_before++;
        tree.nodes[level_first + i] = inner_node(node.axis, node.split, children_first + child);
        for (std::uint32_t c = 0; c < 2; ++c) {
          const std::uint32_t index = c == 0 ? node.a : node.b;
          children[child + c] = (index & kSpawnedBit) ? Entry{&in->spawned[index & ~kSpawnedBit], 0}
                                                      : Entry{in, index};
        }
      }
    });
    level_first = children_first;
    leaf_first += chunk_first[chunks].leaf_entries;
    n = 2 * inner;
    std::swap(level, next);
    current = level.data();
  }
}

}  // namespace cohort::kd
