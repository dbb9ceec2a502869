// The binary BVH of runtime/accel/binary_bvh.h collapsed into wide nodes with one box per lane and
// 4-wide child references (types.h): the 4-wide BVH's Bvh4Node (runtime/accel/bvh4.cpp) and the
// 8-wide BVH with float planes' Bvh8fNode (runtime/accel/bvh8f.cpp), one collapse for both widths.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "kernels/common/accel/bvh4_traverse.h"
#include "kernels/common/core/types.h"
#include "runtime/accel/binary_bvh.h"
#include "runtime/accel/bvh4.h"
#include "runtime/util/error.h"

namespace cohort::wide_collapse {

using binary_bvh::Box;

// Boxes grow by `pad` on every side: the watertight test reports a hit on a shared edge or vertex
// for a ray that, rounded otherwise, passes a few ulps outside that triangle's box, and the box
// must still let it in (bvh4_traverse.h).
inline void set_lane(Bvh4Node& node, int lane, const Box& b, std::uint32_t child, float pad) {
  float* lanes[6] = {&node.lo_x.x, &node.hi_x.x, &node.lo_y.x, &node.hi_y.x, &node.lo_z.x, &node.hi_z.x};
  for (int a = 0; a < 3; ++a) {
    lanes[2 * a][lane] = b.lo[a] - pad;
    lanes[2 * a + 1][lane] = b.hi[a] + pad;
  }
  (&node.child.x)[lane] = child;
}

inline void set_lane(Bvh8fNode& node, int lane, const Box& b, std::uint32_t child, float pad) {
  for (int a = 0; a < 3; ++a) {
    node.planes[2 * a][lane] = b.lo[a] - pad;
    node.planes[2 * a + 1][lane] = b.hi[a] + pad;
  }
  node.child[lane] = child;
}

// The binary tree collapsed into `Width`-wide nodes, depth first (each node before its children, a
// lane's subtree after the lanes before it). A first pass counts each wide node's subtree, so the
// second knows where every subtree goes and both run in parallel over large subtrees; the result
// is the nodes of a serial depth-first walk, the same for any thread count.
template <class WideNode, int Width>
struct Collapser {
  const binary_bvh::Tree& b;
  float pad;  // 2^-20 of the largest coordinate: far above the rounding of any vertex
  // Per binary slot that roots a wide node: that node's subtree size in wide nodes.
  std::unique_ptr<std::uint32_t[]> subtree_nodes;
  WideNode* out = nullptr;
  // Per reference entry that starts a leaf: the leaf's first block of four triangles, for a layout
  // whose leaves are blocks (Bvh8f); null where a leaf names its first entry.
  const std::uint32_t* leaf_block = nullptr;
  binary_bvh::LeafShape shape;  // what the leaves cost, for the SAH figure

  using Sums = binary_bvh::SubtreeSums;
  using Kids = std::array<std::uint32_t, Width>;

  Collapser(const binary_bvh::Tree& builder, float pad_)
      : b(builder), pad(pad_), subtree_nodes(std::make_unique_for_overwrite<std::uint32_t[]>(b.slots)) {}

  // Which binary nodes become the lanes of each wide node. With least_sah (the 8-wide BVH with float
  // planes, for CPUs): the choice that minimises the tree's SAH (the cost emit sums), made bottom-up
  // over the binary tree before the collapse (plan). The 4-wide BVH keeps the widest-first rule,
  // which traced 1-4 % faster on a GPU (docs/design.md, "Collapsing the binary tree"). For a
  // subtree x and a budget of j lanes, D(x, j) is the least cost of covering x with at most j lanes:
  // x itself in one lane (a leaf, or an inner node that roots a wide node of its own: kNodeCost times
  // its area plus its children spread over Width lanes) or x opened, its children sharing the j lanes
  // k and j - k. A lane's subtree gets at most Width - 1 of its parent's lanes, so D is kept for
  // budgets 1 to Width - 1. `open_lanes` keeps, per inner slot, the best k for each budget j of 2 to
  // Width (3 bits each, from bit 0) and for j below Width whether one lane did better (a bit each,
  // from bit kWholeBits).
  static_assert(Width >= 2 && Width <= 8, "open_lanes packs 4 bits per lane budget");
  static constexpr int kWholeBits = 3 * (Width - 1);
  using Costs = std::array<double, Width>;  // D(x, j) at [j], j = 1..Width - 1
  bool least_sah = false;
  std::unique_ptr<std::uint32_t[]> open_lanes;  // plan's choices, with least_sah

  static int split_of(std::uint32_t packed, int j) { return int((packed >> (3 * (j - 2))) & 7u) + 1; }
  static bool whole_at(std::uint32_t packed, int j) { return (packed >> (kWholeBits + j - 2)) & 1u; }

  Costs plan(std::uint32_t slot) {
    const binary_bvh::Node& x = b.nodes[slot];
    Costs d{};
    if (x.count) {
      d.fill(double(x.box().area()) * shape.tests(x.count));
      return d;
    }
    std::array<Costs, 2> kid;
    const std::uint32_t children[2] = {x.left, x.right};
    binary_bvh::for_children(x.references, 2, [&](int i) { kid[i] = plan(children[i]); });
    std::uint32_t packed = 0;
    std::array<double, Width + 1> opened{};  // x opened into at most j lanes, at [j]
    for (int j = 2; j <= Width; ++j) {
      int best_k = 1;
      double best = kid[0][1] + kid[1][j - 1];
      for (int k = 2; k < j; ++k) {
        const double c = kid[0][k] + kid[1][j - k];
        if (c < best) { best = c; best_k = k; }
      }
      opened[j] = best;
      packed |= std::uint32_t(best_k - 1) << (3 * (j - 2));
    }
    const double whole = binary_bvh::kNodeCost * double(x.box().area()) + opened[Width];
    d[1] = whole;
    for (int j = 2; j < Width; ++j) {
      d[j] = std::min(whole, opened[j]);
      if (whole <= opened[j]) packed |= 1u << (kWholeBits + j - 2);
    }
    open_lanes[slot] = packed;
    return d;
  }

  // Adds the lanes that cover subtree `slot` with at most `budget` lanes, as plan chose, to kids.
  void spread(std::uint32_t slot, int budget, Kids& kids, int& n) const {
    if (b.nodes[slot].count || budget == 1 || whole_at(open_lanes[slot], budget)) {
      kids[n++] = slot;
      return;
    }
    open(slot, budget, kids, n);
  }

  // Adds the lanes of inner node `slot` opened: its children sharing `budget` lanes as plan chose.
  void open(std::uint32_t slot, int budget, Kids& kids, int& n) const {
    const int k = split_of(open_lanes[slot], budget);
    spread(b.nodes[slot].left, k, kids, n);
    spread(b.nodes[slot].right, budget - k, kids, n);
  }

  // The lanes of the wide node at binary node `slot` (a root that is a leaf: one lane): with
  // least_sah its subtree spread over Width lanes as plan chose; else its children, then the inner
  // child of largest area opened until every lane is full (Embree's rule).
  int lanes(std::uint32_t slot, Kids& kids) const {
    int n = 0;
    if (b.nodes[slot].count) {
      kids[n++] = slot;
      return n;
    }
    if (least_sah) {
      open(slot, Width, kids, n);
      return n;
    }
    kids[n++] = b.nodes[slot].left;
    kids[n++] = b.nodes[slot].right;
    // each kid's area once (a leaf's is never compared)
    std::array<float, Width> area{};
    const auto measure = [&](int i) {
      const binary_bvh::Node& k = b.nodes[kids[i]];
      area[i] = k.count ? -1.0f : k.box().area();
    };
    for (int i = 0; i < n; ++i) measure(i);
    while (n < Width) {
      int widest = -1;
      for (int i = 0; i < n; ++i) {
        if (!(area[i] < 0.0f) && (widest < 0 || area[i] > area[widest])) widest = i;
      }
      if (widest < 0) break;
      const binary_bvh::Node& k = b.nodes[kids[widest]];
      kids[widest] = k.left;
      kids[n] = k.right;
      measure(widest);
      measure(n++);
    }
    return n;
  }

  std::uint32_t count(std::uint32_t slot) {
    Kids kids{};
    const int n = lanes(slot, kids);
    std::array<std::uint32_t, Width> counts{};
    binary_bvh::for_children(b.nodes[slot].references, n, [&](int lane) {
      if (!b.nodes[kids[lane]].count) counts[lane] = count(kids[lane]);
    });
    std::uint32_t total = 1;
    for (const std::uint32_t c : counts) total += c;
    return subtree_nodes[slot] = total;
  }

  // Writes the wide node for binary node `slot` at `index`, and its subtree after it.
  Sums emit(std::uint32_t slot, std::uint32_t index, int depth) {
    Kids kids{};
    const int n = lanes(slot, kids);
    std::array<std::uint32_t, Width> child_index{};
    std::uint32_t next = index + 1;
    for (int lane = 0; lane < n; ++lane) {
      if (b.nodes[kids[lane]].count) continue;
      child_index[lane] = next;
      next += subtree_nodes[kids[lane]];
    }
    std::array<Sums, Width> lane_sums{};
    binary_bvh::for_children(b.nodes[slot].references, n, [&](int lane) {
      if (!b.nodes[kids[lane]].count) lane_sums[lane] = emit(kids[lane], child_index[lane], depth + 1);
    });
    WideNode node{};
    const Box empty{{INFINITY, INFINITY, INFINITY}, {INFINITY, INFINITY, INFINITY}};
    for (int lane = 0; lane < Width; ++lane) set_lane(node, lane, empty, BVH4_EMPTY, 0.0f);
    Sums sums;
    sums.depth = depth;
    sums.sah = binary_bvh::kNodeCost * b.nodes[slot].box().area();
    for (int lane = 0; lane < n; ++lane) {
      const binary_bvh::Node& k = b.nodes[kids[lane]];
      std::uint32_t child = child_index[lane];
      if (k.count) {
        child = bvh4_leaf_ref(leaf_block ? leaf_block[k.first] : k.first, k.count);
        ++sums.leaves;
        sums.sah += k.box().area() * shape.tests(k.count);
      }
      sums.add(lane_sums[lane]);
      set_lane(node, lane, k.box(), child, pad);
    }
    out[index] = node;
    return sums;
  }

  // The wide tree into `nodes` (resized to fit).
  Sums collapse(std::vector<WideNode>& nodes) {
    if (least_sah) {
      open_lanes = std::make_unique_for_overwrite<std::uint32_t[]>(b.slots);
      plan(0);
    }
    nodes.resize(count(0));
    out = nodes.data();
    return emit(0, 0, 1);
  }
};

static_assert(binary_bvh::kMaxDepth <= BVH4_MAX_DEPTH, "the traversal stack must hold the deepest tree");

// Triangles per leaf of both wide BVHs (BVH4_LEAF_MAX allows up to 16).
inline constexpr std::uint32_t kMaxLeaf = 4;

// The leaves of `binary` as blocks of four triangles (types.h, Triangle4), leaf after leaf in entry
// order, a leaf of n entries in ceil(n / 4) blocks, each lane a copy of its entry's kept triangle
// and that triangle's index, the unused lanes of a leaf's last block its last entry's. Sets
// first_block[e] to its leaf's first block for each entry e that starts a leaf. A serial pass (a
// few milliseconds per million references).
inline void make_leaf_blocks(const binary_bvh::Tree& binary, std::span<const Triangle> triangles,
                             std::vector<std::uint32_t>& first_block, std::vector<Triangle4>& blocks) {
  // each leaf's entry count at its first entry (overwritten by its first block below)
  first_block.assign(binary.size, 0u);
  std::size_t block_count = 0;
  std::vector<std::uint32_t> stack{0u};
  while (!stack.empty()) {
    const binary_bvh::Node& n = binary.nodes[stack.back()];
    stack.pop_back();
    if (n.count) {
      first_block[n.first] = n.count;
      block_count += bvh8f_leaf_blocks(n.count);
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  blocks.clear();
  blocks.reserve(block_count);
  for (std::size_t first = 0; first < binary.size;) {
    const std::uint32_t count = first_block[first];
    first_block[first] = static_cast<std::uint32_t>(blocks.size());
    for (std::uint32_t b = 0; b < bvh8f_leaf_blocks(count); ++b) {
      Triangle4 block{};
      for (std::uint32_t lane = 0; lane < 4; ++lane) {
        const std::uint32_t tri = binary.triangle_of(first + std::min(4 * b + lane, count - 1));
        const Triangle& t = triangles[tri];
        const co_float4* vertex[3] = {&t.v0, &t.v1, &t.v2};
        for (int v = 0; v < 3; ++v)
          for (int axis = 0; axis < 3; ++axis) (&block.v[v][axis].x)[lane] = (&vertex[v]->x)[axis];
        block.index[lane] = tri;
      }
      blocks.push_back(block);
    }
    first += count;
  }
}

// A wide BVH (Bvh4, Bvh8f: `nodes`, `leaf_vertices` or `leaf_blocks`, `stats`) of `triangles`: the
// binary SAH tree with leaves of kMaxLeaf references, collapsed `Width` wide, each leaf entry a copy
// of its kept triangle with the triangle's index (in v0.w, or a block's lane with its index).
// `tree` names the layout in errors (its --tree value); throws
// InputError for an empty input or more references than a leaf reference can name. The caller sets
// stats.build_seconds (a layout may reorder the nodes after this).
template <int Width, class Bvh>
void build(Bvh& bvh, std::span<const Triangle> triangles, const char* tree) {
  using Node = typename decltype(bvh.nodes)::value_type;
  if (triangles.empty()) throw InputError("a BVH needs at least one triangle");
  if (triangles.size() > BVH4_LEAF_FIRST_MAX)
    throw InputError(fmt::format("the scene has {} triangles; the {} takes at most {}: use --tree deep or compact",
                                 triangles.size(), tree, BVH4_LEAF_FIRST_MAX));
  // before the build (which takes at most the positions it can name) and after it (spatial splits
  // add references)
  const auto check_references = [&](std::size_t references) {
    if (references > BVH4_LEAF_FIRST_MAX)
      throw InputError(fmt::format("the scene's {} triangles make {} BVH references; the {} takes at most {}: use "
                                   "--tree deep or compact",
                                   triangles.size(), references, tree, BVH4_LEAF_FIRST_MAX));
  };
  const binary_bvh::ReferenceChunks references = binary_bvh::make_references(triangles);
  check_references(references.size);
  // leaves tested four triangles at a time cost about one triangle test per block (LeafShape)
  constexpr bool kBlocks = requires { bvh.leaf_blocks; };
  const binary_bvh::LeafShape shape =
      kBlocks ? binary_bvh::LeafShape{kMaxLeaf, 4u, 0.125f} : binary_bvh::LeafShape{kMaxLeaf};
  // spatial splits in both wide BVHs of this collapse, where they were measured: the CPU's (the
  // Sponza interior 1.14x on PoCL, the same elsewhere) and the GPUs' 4-wide one (the Sponza interior
  // on an H100: path tracing 1.12-1.16x, diffuse rays 1.20x); docs/design.md, "Spatial splits"
  const binary_bvh::Tree binary = binary_bvh::build(references, triangles, shape);
  check_references(binary.size);
  Collapser<Node, Width> collapser{binary, binary.pad()};
  collapser.shape = shape;
  collapser.least_sah = kBlocks;  // the CPU's tree (the Collapser's lanes say why not the GPU's)
  std::vector<std::uint32_t> first_block;
  std::size_t leaf_bytes = 0;
  if constexpr (kBlocks) {
    make_leaf_blocks(binary, triangles, first_block, bvh.leaf_blocks);
    collapser.leaf_block = first_block.data();
    leaf_bytes = bvh.leaf_blocks.size() * sizeof(Triangle4);
  } else {
    bvh.leaf_vertices.resize(binary.size);
    binary_bvh::parallel_chunks(binary.size, [&](std::size_t i) {
      const std::uint32_t tri = binary.triangle_of(i);
      bvh.leaf_vertices[i] = triangles[tri];
      bvh.leaf_vertices[i].v0.w = co_as_float(tri);
    });
    leaf_bytes = bvh.leaf_vertices.size() * sizeof(Triangle);
  }
  const binary_bvh::SubtreeSums sums = collapser.collapse(bvh.nodes);
  bvh.stats.node_count = bvh.nodes.size();
  bvh.stats.references = binary.size;
  bvh.stats.leaf_count = sums.leaves;
  bvh.stats.depth = sums.depth;
  bvh.stats.average_leaf_triangles = double(binary.size) / double(bvh.stats.leaf_count);
  const float root_area = binary.nodes[0].box().area();
  bvh.stats.sah_cost = root_area > 0 ? sums.sah / root_area : 0.0;
  bvh.stats.bytes = bvh.nodes.size() * sizeof(Node) + leaf_bytes;
}

}  // namespace cohort::wide_collapse
