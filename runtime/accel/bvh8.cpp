// build_bvh8: the binary BVH of runtime/accel/binary_bvh.h collapsed into compressed 8-wide nodes. A
// first pass counts each 8-wide node's subtree, so the second knows where every node and triangle
// goes and both run in parallel over large subtrees; the result does not depend on the thread count.
#include "runtime/accel/bvh8.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "kernels/common/accel/bvh8_traverse.h"
#include "runtime/accel/binary_bvh.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

using binary_bvh::Box;
using binary_bvh::kNodeCost;

constexpr int kWidth = 8;
static_assert(binary_bvh::kMaxDepth + 1 <= BVH8_STACK, "the traversal stack must hold a group per level");

// A node's children: binary nodes, each an inner node or a leaf of at most BVH8_LEAF_MAX references.
struct Children {
  std::array<std::uint32_t, kWidth> node{};
  std::array<bool, kWidth> leaf{};
  int count = 0;
};

// One axis of a node's grid: planes are origin + q * 2^exponent, q in 0-255.
struct Grid {
  int exponent = 0;
  double origin = 0;  // a float, and a multiple of 2^exponent
  double step() const { return std::ldexp(1.0, exponent); }
};

// The grid for planes in [lo, hi] (the node's padded box on one axis): the paper's exponent,
// ceil(log2((hi - lo) / 255)), raised where needed so that every multiple of 2^e the node uses is a
// float (then origin + q * 2^e is exact in float, with or without fma) and so that hi still fits in
// 255 steps above the origin rounded down onto the grid. The exponent is at least -100: the node test
// multiplies 2^e by the ray's inverse direction (bvh8_traverse.h, bvh8_grid), which must not be
// subnormal, as GPUs flush those to zero.
Grid grid_for(float lo, float hi) {
  const double extent = double(hi) - double(lo);
  Grid g;
  g.exponent = extent > 0 ? std::ilogb(extent / 255.0) : -100;
  while (std::ldexp(255.0, g.exponent) < extent) ++g.exponent;
  const float largest = std::max(std::fabs(lo), std::fabs(hi));
  if (largest > 0) g.exponent = std::max(g.exponent, std::ilogb(largest) - 23);
  g.exponent = std::max(g.exponent, -100);
  for (;; ++g.exponent) {
    if (g.exponent > 127) throw std::logic_error("bvh8: a box too large for a float exponent");
    const double s = g.step();
    g.origin = std::floor(double(lo) / s) * s;
    if (std::ceil((double(hi) - g.origin) / s) <= 255.0) return g;
  }
}

// The plane origin + q * step as the traversal computes it in float, checked to be exactly the
// double value (so conservative rounding in double is conservative on the device).
float decoded(const Grid& g, int q) {
  const float f = float(g.origin) + float(q) * float(g.step());
  if (double(f) != g.origin + q * g.step()) throw std::logic_error("bvh8: a quantised plane is not exact in float");
  return f;
}

std::uint32_t unary(std::uint32_t count) { return (1u << count) - 1u; }

struct Bvh8Collapser {
  const binary_bvh::Tree& b;
  std::span<const Triangle> triangles;
  float pad;  // as the 4-wide BVH's boxes (bvh4_traverse.h says why)
  // Per binary node that roots an 8-wide node: that node's subtree size in 8-wide nodes.
  std::unique_ptr<std::uint32_t[]> subtree_nodes;
  Bvh8Node* out_nodes = nullptr;
  Triangle* out_triangles = nullptr;

  using Sums = binary_bvh::SubtreeSums;

  Bvh8Collapser(const binary_bvh::Tree& tree, std::span<const Triangle> tris)
      : b(tree), triangles(tris), pad(tree.pad()),
        subtree_nodes(std::make_unique_for_overwrite<std::uint32_t[]>(b.slots)) {}

  // The children of the 8-wide node at binary node `slot`: its two children, then the inner child of
  // largest area opened until eight are there; an inner child left with no more references than a
  // leaf holds becomes a leaf (a node visit saved for the same triangle tests).
  Children children(std::uint32_t slot) const {
    Children c;
    std::array<float, kWidth> area{};
    const auto add = [&](int i, std::uint32_t node) {
      const binary_bvh::Node& k = b.nodes[node];
      c.node[i] = node;
      c.leaf[i] = k.count != 0;
      area[i] = c.leaf[i] ? -1.0f : k.box().area();
    };
    if (b.nodes[slot].count) {
      add(c.count++, slot);
    } else {
      add(c.count++, b.nodes[slot].left);
      add(c.count++, b.nodes[slot].right);
    }
    while (c.count < kWidth) {
      int widest = -1;
      for (int i = 0; i < c.count; ++i)
        if (!c.leaf[i] && (widest < 0 || area[i] > area[widest])) widest = i;
      if (widest < 0) break;
      const binary_bvh::Node& k = b.nodes[c.node[widest]];
      add(widest, k.left);
      add(c.count++, k.right);
    }
    for (int i = 0; i < c.count; ++i)
      if (b.nodes[c.node[i]].references <= BVH8_LEAF_MAX) c.leaf[i] = true;
    return c;
  }

  // The paper's slot assignment: slot s is for rays whose direction has the signs of s (bit a set
  // for a negative component on axis a); placing child i there costs the dot product of its centre's
  // offset from the parent's centre with that direction, so the child that comes first along it has
  // the least cost. The least cost over the free pairs is taken until every child has a slot (the
  // first pair in (child, slot) order at equal costs). Returns the child in each slot, or -1.
  std::array<int, kWidth> slots(std::uint32_t parent, const Children& c) const {
    const Box p = b.nodes[parent].box();
    std::array<std::array<float, kWidth>, kWidth> cost{};
    for (int i = 0; i < c.count; ++i) {
      const Box k = b.nodes[c.node[i]].box();
      for (int s = 0; s < kWidth; ++s) {
        float sum = 0.0f;
        for (int a = 0; a < 3; ++a) {
          const float offset = (k.lo[a] + k.hi[a]) - (p.lo[a] + p.hi[a]);
          sum += (s >> a) & 1 ? -offset : offset;
        }
        cost[i][s] = sum;
      }
    }
    std::array<int, kWidth> child_in{};
    child_in.fill(-1);
    std::array<bool, kWidth> placed{};
    for (int round = 0; round < c.count; ++round) {
      int best_i = -1, best_s = -1;
      for (int i = 0; i < c.count; ++i) {
        if (placed[i]) continue;
        for (int s = 0; s < kWidth; ++s)
          if (child_in[s] < 0 && (best_i < 0 || cost[i][s] < cost[best_i][best_s])) {
            best_i = i;
            best_s = s;
          }
      }
      placed[best_i] = true;
      child_in[best_s] = best_i;
    }
    return child_in;
  }

  std::uint32_t count(std::uint32_t slot) {
    const Children c = children(slot);
    std::array<std::uint32_t, kWidth> counts{};
    binary_bvh::for_children(b.nodes[slot].references, c.count, [&](int i) {
      if (!c.leaf[i]) counts[i] = count(c.node[i]);
    });
    std::uint32_t total = 1;
    for (const std::uint32_t n : counts) total += n;
    return subtree_nodes[slot] = total;
  }

  // Writes the 8-wide node for binary node `slot` at `index`; its inner children go to `region` on
  // (consecutive, in slot order), their subtrees after them in the same order; its leaf children's
  // triangles to `first_triangle` on, then the inner children's subtrees' in slot order.
  Sums emit(std::uint32_t slot, std::uint32_t index, std::uint32_t region, std::uint32_t first_triangle, int depth) {
    const Children c = children(slot);
    const std::array<int, kWidth> child_in = slots(slot, c);

    // the padded child boxes and the node's box around them
    std::array<std::array<float, 3>, kWidth> lo{}, hi{};
    Box node_box;
    for (int i = 0; i < c.count; ++i) {
      const Box k = b.nodes[c.node[i]].box();
      for (int a = 0; a < 3; ++a) {
        lo[i][a] = k.lo[a] - pad;
        hi[i][a] = k.hi[a] + pad;
      }
      node_box.extend(Box{lo[i], hi[i]});
    }
    std::array<Grid, 3> grid;
    for (int a = 0; a < 3; ++a) grid[a] = grid_for(node_box.lo[a], node_box.hi[a]);

    Bvh8Node node{};
    std::uint32_t imask = 0, meta[kWidth] = {}, words[12] = {};
    std::uint32_t inner = 0, leaf_triangles = 0;
    for (int s = 0; s < kWidth; ++s) {
      const int i = child_in[s];
      if (i < 0) continue;
      if (c.leaf[i]) {
        const std::uint32_t n = b.nodes[c.node[i]].references;
        meta[s] = (unary(n) << 5) | leaf_triangles;
        leaf_triangles += n;
      } else {
        imask |= 1u << s;
        meta[s] = 0x20u | (24u + s);
        ++inner;
      }
      for (int a = 0; a < 3; ++a) {
        const Grid& g = grid[a];
        const double step = g.step();
        const int q_lo = int(std::floor((double(lo[i][a]) - g.origin) / step));
        const int q_hi = int(std::ceil((double(hi[i][a]) - g.origin) / step));
        if (q_lo < 0 || q_hi > 255 || q_lo > q_hi || decoded(g, q_lo) > lo[i][a] || decoded(g, q_hi) < hi[i][a])
          throw std::logic_error("bvh8: a child box outside its node's grid");
        words[2 * a + s / 4] |= std::uint32_t(q_lo) << (8 * (s % 4));
        words[2 * (a + 3) + s / 4] |= std::uint32_t(q_hi) << (8 * (s % 4));
      }
    }
    node.header = co_make_uint4(co_as_uint(float(grid[0].origin)), co_as_uint(float(grid[1].origin)),
                                co_as_uint(float(grid[2].origin)),
                                std::uint32_t(grid[0].exponent + 127) | std::uint32_t(grid[1].exponent + 127) << 8 |
                                    std::uint32_t(grid[2].exponent + 127) << 16 | imask << 24);
    node.index = co_make_uint4(region, first_triangle, meta[0] | meta[1] << 8 | meta[2] << 16 | meta[3] << 24,
                               meta[4] | meta[5] << 8 | meta[6] << 16 | meta[7] << 24);
    std::memcpy(node.q, words, sizeof(words));
    out_nodes[index] = node;

    // where each inner child and its subtree go, and each leaf's triangles
    std::array<std::uint32_t, kWidth> child_index{}, child_region{}, child_triangles{};
    std::uint32_t next_region = region + inner, next_triangle = first_triangle + leaf_triangles, j = 0;
    Sums sums;
    sums.depth = depth;
    sums.sah = kNodeCost * b.nodes[slot].box().area();
    for (int s = 0; s < kWidth; ++s) {
      const int i = child_in[s];
      if (i < 0) continue;
      const binary_bvh::Node& k = b.nodes[c.node[i]];
      if (c.leaf[i]) {
        const std::uint32_t at = first_triangle + (meta[s] & 31u);
        for (std::uint32_t t = 0; t < k.references; ++t) {
          const std::uint32_t tri = b.triangle_of(k.first + t);
          out_triangles[at + t] = triangles[tri];
          out_triangles[at + t].v0.w = co_as_float(tri);
        }
        ++sums.leaves;
        sums.sah += k.box().area() * k.references;
        continue;
      }
      child_index[i] = region + j++;
      child_region[i] = next_region;
      child_triangles[i] = next_triangle;
      next_region += subtree_nodes[c.node[i]] - 1;
      next_triangle += k.references;
    }
    std::array<Sums, kWidth> child_sums{};
    binary_bvh::for_children(b.nodes[slot].references, c.count, [&](int i) {
      if (!c.leaf[i]) child_sums[i] = emit(c.node[i], child_index[i], child_region[i], child_triangles[i], depth + 1);
    });
    for (const Sums& s : child_sums) sums.add(s);
    return sums;
  }

  Sums collapse(Bvh8& bvh) {
    bvh.nodes.resize(count(0));
    bvh.leaf_vertices.resize(b.size);
    out_nodes = bvh.nodes.data();
    out_triangles = bvh.leaf_vertices.data();
    return emit(0, 0, 1, 0, 1);
  }
};

}  // namespace

std::array<float, 6> bvh8_child_box(const Bvh8Node& node, int slot) {
  std::uint32_t words[12];
  std::memcpy(words, node.q, sizeof(words));
  std::array<float, 6> box{};
  const std::uint32_t origin[3] = {node.header.x, node.header.y, node.header.z};
  for (int p = 0; p < 6; ++p) {
    const int a = p % 3;
    const float scale = co_as_float(((node.header.w >> (8 * a)) & 255u) << 23);
    const std::uint32_t q = (words[2 * p + slot / 4] >> (8 * (slot % 4))) & 255u;
    box[p] = co_as_float(origin[a]) + float(q) * scale;
  }
  return box;
}

Bvh8 build_bvh8(std::span<const Triangle> triangles) {
  const auto start = std::chrono::steady_clock::now();
  if (triangles.empty()) throw InputError("a BVH needs at least one triangle");
  // The node test's products stay finite within this bound (bvh8_traverse.h, bvh8_grid): a ray's
  // distance to a plane is q * 2^e * inverse + (origin - o) * inverse with |inverse| up to 1e18.
  constexpr float kFarthest = 1e19f;
  for (const Triangle& t : triangles)
    for (const co_float4& v : {t.v0, t.v1, t.v2})
      if (!(std::fabs(v.x) <= kFarthest && std::fabs(v.y) <= kFarthest && std::fabs(v.z) <= kFarthest))
        throw InputError(fmt::format("the 8-wide BVH (--tree bvh8) takes vertices within {:g} of the origin; the "
                                     "scene reaches ({:g}, {:g}, {:g}): use --tree bvh4",
                                     kFarthest, v.x, v.y, v.z));
  const binary_bvh::ReferenceChunks references = binary_bvh::make_references(triangles);
  constexpr std::size_t kMost = (std::size_t{1} << 31) - 1;  // binary slots 2n - 1 in 32 bits
  if (references.size > kMost)
    throw InputError(fmt::format("the scene's {} triangles make {} BVH references; the 8-wide BVH (--tree bvh8) "
                                 "takes at most {}: use --tree deep or compact",
                                 triangles.size(), references.size, kMost));
  // object splits alone: spatial splits were measured on the other two BVHs, not on this one
  const binary_bvh::Tree binary = binary_bvh::build(references, triangles, {BVH8_LEAF_MAX, 1u}, false);
  Bvh8 bvh;
  Bvh8Collapser collapser(binary, triangles);
  const Bvh8Collapser::Sums sums = collapser.collapse(bvh);
  bvh.stats.node_count = bvh.nodes.size();
  bvh.stats.references = binary.size;
  bvh.stats.leaf_count = sums.leaves;
  bvh.stats.depth = sums.depth;
  bvh.stats.average_leaf_triangles = double(binary.size) / double(bvh.stats.leaf_count);
  const float root_area = binary.nodes[0].box().area();
  bvh.stats.sah_cost = root_area > 0 ? sums.sah / root_area : 0.0;
  bvh.stats.bytes = bvh.nodes.size() * sizeof(Bvh8Node) + bvh.leaf_vertices.size() * sizeof(Triangle);
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace cohort
