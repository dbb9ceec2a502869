// The binary BVH that the wide BVHs collapse (runtime/accel/bvh4.h: 4-wide; runtime/accel/bvh8.h: the
// compressed 8-wide one): references (triangles, large ones split into parts), a binned-SAH binary
// tree over them, and what both collapses share.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/common/core/types.h"

namespace cohort::binary_bvh {

constexpr std::uint32_t kParallelTriangles = 4096;  // subtrees of at least this many references build in parallel
constexpr float kNodeCost = 0.5f;                    // a wide node's box test against one triangle test
constexpr int kMaxDepth = 59;                        // the deepest leaf's depth (build says why)

struct Box {
  std::array<float, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  void extend(const Box& b) {
    for (int a = 0; a < 3; ++a) { lo[a] = std::min(lo[a], b.lo[a]); hi[a] = std::max(hi[a], b.hi[a]); }
  }
  void extend(const std::array<float, 3>& p) {
    for (int a = 0; a < 3; ++a) { lo[a] = std::min(lo[a], p[a]); hi[a] = std::max(hi[a], p[a]); }
  }
  float area() const {
    float d[3];
    for (int a = 0; a < 3; ++a) d[a] = std::max(0.0f, hi[a] - lo[a]);
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
  }
};

// A binary node; count > 0 marks a leaf of triangles [first, first + count) of the reference list.
// Trivial, so the slots are allocated without being cleared: the build writes every one it uses.
struct Node {
  std::array<float, 3> lo, hi;
  std::uint32_t first, count;
  std::uint32_t references;  // in the subtree: [first, first + references)
  std::uint32_t left, right;
  Box box() const { return Box{lo, hi}; }
};
static_assert(std::is_trivially_default_constructible_v<Node>);

// A part of a triangle the tree sorts on its own: the triangle's index and a box around its part.
struct Reference {
  Box box;
  std::uint32_t triangle;
};

// The references of fixed chunks of triangles, each chunk's in triangle order: joined in chunk
// order, the same references for any thread count.
struct ReferenceChunks {
  std::vector<std::vector<Reference>> chunks;
  std::size_t size = 0;  // references in all chunks
};

// Early split clipping (make_references in binary_bvh.cpp says how and why).
ReferenceChunks make_references(std::span<const Triangle> triangles);

// What a subtree of a wide BVH adds to the tree's statistics, summed as a collapse emits it (in
// lane or slot order, so the sums do not depend on the thread count).
struct SubtreeSums {
  std::size_t leaves = 0;
  int depth = 0;
  double sah = 0;  // area x cost over nodes and leaves; divided by the root's area at the end
  void add(const SubtreeSums& o) {
    leaves += o.leaves;
    depth = std::max(depth, o.depth);
    sah += o.sah;
  }
};


struct Tree {
  std::size_t size = 0;                       // references
  std::size_t slots = 0;                      // node slots, some unused: what per-slot arrays need
  std::unique_ptr<Node[]> nodes;              // node 0 is the root; the slots of a subtree follow it
  std::unique_ptr<std::uint32_t[]> triangle;  // per leaf entry, in leaf order: its triangle
  // The triangle of leaf entry i (the leaves name entries [first, first + count)).
  std::uint32_t triangle_of(std::size_t entry) const { return triangle[entry]; }
  // 2^-20 of the largest coordinate of the root's box: what the wide nodes pad their boxes by (far
  // above the rounding of any vertex; bvh4_traverse.h says why a box needs it).
  float pad() const;
};

// What a leaf may hold and what testing it costs: at most `max_leaf` references, tested `block` at a
// time. A leaf of n costs n triangle tests where block is 1 (the GPU's trees, which test one triangle
// after another); otherwise a full block costs one test, of which `per_triangle` for each triangle
// it holds and the rest for the block's loads and set-up (the CPU's tree, whose leaves are tested
// four triangles to a float4 step: block 4, per_triangle 1/8, so a leaf of one triangle costs 5/8).
struct LeafShape {
  std::uint32_t max_leaf = 4;
  std::uint32_t block = 1;
  float per_triangle = 0.0f;
  // The SAH cost of a leaf of n references, in triangle tests.
  float tests(std::uint32_t n) const {
    if (block == 1u) return float(n);
    return float((n + block - 1u) / block) * (1.0f - float(block) * per_triangle) + per_triangle * float(n);
  }
};

// Binned SAH over reference centroids (Wald, "On fast construction of SAH-based bounding volume
// hierarchies", 2007), with spatial splits where the SAH prefers them (binary_bvh.cpp), leaves as
// `shape` says, object-median splits from depth 32 on (so at most 59 levels). `triangles` are the
// references' triangles; `spatial_splits` false builds with object splits alone (the tests compare
// the two). The same tree for any thread count.
Tree build(const ReferenceChunks& references, std::span<const Triangle> triangles, LeafShape shape,
           bool spatial_splits = true);

// f(i) for every i below n, in parallel over chunks of kParallelTriangles.
template <class F>
void parallel_chunks(std::size_t n, const F& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kParallelTriangles),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) f(i);
                    });
}

// f(i) for each of the n children of a node of the binary tree that hold `references` references
// between them: in parallel where that subtree is large (a collapse into wide nodes counts and
// emits their subtrees so), else in order.
template <class F>
void for_children(std::uint32_t references, int n, const F& f) {
  if (references >= kParallelTriangles) {
    tbb::parallel_for(0, n, f);
  } else {
    for (int i = 0; i < n; ++i) f(i);
  }
}

}  // namespace cohort::binary_bvh
