// build_bvh4: the binary BVH of runtime/accel/binary_bvh.h collapsed into 4-wide nodes depth first.
#include "runtime/accel/bvh4.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>

#include "kernels/common/accel/bvh4_traverse.h"
#include "runtime/accel/binary_bvh.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

using binary_bvh::Box;
using binary_bvh::kNodeCost;
using Node2 = binary_bvh::Node;

constexpr std::uint32_t kMaxLeaf = 4;  // triangles; BVH4_LEAF_MAX allows up to 16
static_assert(binary_bvh::kMaxDepth <= BVH4_MAX_DEPTH, "the traversal stack must hold the deepest tree");


// Boxes grow by `pad` on every side: the watertight test reports a hit on a shared edge or vertex
// for a ray that, rounded otherwise, passes a few ulps outside that triangle's box, and the box
// must still let it in (bvh4_traverse.h).
void set_lane(Bvh4Node& node, int lane, const Box& b, std::uint32_t child, float pad) {
  float* lanes[6] = {&node.lo_x.x, &node.hi_x.x, &node.lo_y.x, &node.hi_y.x, &node.lo_z.x, &node.hi_z.x};
  for (int a = 0; a < 3; ++a) {
    lanes[2 * a][lane] = b.lo[a] - pad;
    lanes[2 * a + 1][lane] = b.hi[a] + pad;
  }
  (&node.child.x)[lane] = child;
}

// The binary tree collapsed into 4-wide nodes, depth first (each node before its children, a
// lane's subtree after the lanes before it). A first pass counts each 4-wide node's subtree, so
// the second knows where every subtree goes and both run in parallel over large subtrees; the
// result is the nodes of a serial depth-first walk.
struct Collapser {
  const binary_bvh::Tree& b;
  float pad;  // 2^-20 of the largest coordinate: far above the rounding of any vertex
  // Per binary slot that roots a 4-wide node: that node's subtree size in 4-wide nodes.
  std::unique_ptr<std::uint32_t[]> subtree_nodes;
  Bvh4Node* out = nullptr;

  using Sums = binary_bvh::SubtreeSums;

  Collapser(const binary_bvh::Tree& builder, float pad_)
      : b(builder), pad(pad_), subtree_nodes(std::make_unique_for_overwrite<std::uint32_t[]>(2 * b.size - 1)) {}

  // The lanes of the 4-wide node at binary node `slot`: its children, then the inner child of
  // largest area opened until four lanes are full.
  int lanes(std::uint32_t slot, std::array<std::uint32_t, 4>& kids) const {
    int n = 0;
    if (b.nodes[slot].count) {
      kids[n++] = slot;  // a root that is a leaf: one lane
    } else {
      kids[n++] = b.nodes[slot].left;
      kids[n++] = b.nodes[slot].right;
    }
    // each kid's area once (a leaf's is never compared)
    std::array<float, 4> area{};
    const auto measure = [&](int i) {
      const Node2& k = b.nodes[kids[i]];
      area[i] = k.count ? -1.0f : k.box().area();
    };
    for (int i = 0; i < n; ++i) measure(i);
    while (n < 4) {
      int widest = -1;
      for (int i = 0; i < n; ++i) {
        if (!(area[i] < 0.0f) && (widest < 0 || area[i] > area[widest])) widest = i;
      }
      if (widest < 0) break;
      const Node2& k = b.nodes[kids[widest]];
      kids[widest] = k.left;
      kids[n] = k.right;
      measure(widest);
      measure(n++);
    }
    return n;
  }

  std::uint32_t count(std::uint32_t slot) {
    std::array<std::uint32_t, 4> kids{};
    const int n = lanes(slot, kids);
    std::array<std::uint32_t, 4> counts{};
    binary_bvh::for_children(b.nodes[slot].references, n, [&](int lane) {
      if (!b.nodes[kids[lane]].count) counts[lane] = count(kids[lane]);
    });
    return subtree_nodes[slot] = 1 + counts[0] + counts[1] + counts[2] + counts[3];
  }

  // Writes the 4-wide node for binary node `slot` at `index`, and its subtree after it.
  Sums emit(std::uint32_t slot, std::uint32_t index, int depth) {
    std::array<std::uint32_t, 4> kids{};
    const int n = lanes(slot, kids);
    std::array<std::uint32_t, 4> child_index{};
    std::uint32_t next = index + 1;
    for (int lane = 0; lane < n; ++lane) {
      if (b.nodes[kids[lane]].count) continue;
      child_index[lane] = next;
      next += subtree_nodes[kids[lane]];
    }
    std::array<Sums, 4> lane_sums{};
    binary_bvh::for_children(b.nodes[slot].references, n, [&](int lane) {
      if (!b.nodes[kids[lane]].count) lane_sums[lane] = emit(kids[lane], child_index[lane], depth + 1);
    });
    Bvh4Node node{};
    const Box empty{{INFINITY, INFINITY, INFINITY}, {INFINITY, INFINITY, INFINITY}};
    for (int lane = 0; lane < 4; ++lane) set_lane(node, lane, empty, BVH4_EMPTY, 0.0f);
    Sums sums;
    sums.depth = depth;
    sums.sah = kNodeCost * b.nodes[slot].box().area();
    for (int lane = 0; lane < n; ++lane) {
      const Node2& k = b.nodes[kids[lane]];
      std::uint32_t child = child_index[lane];
      if (k.count) {
        child = bvh4_leaf_ref(k.first, k.count);
        ++sums.leaves;
        sums.sah += k.box().area() * k.count;
      }
      sums.add(lane_sums[lane]);
      set_lane(node, lane, k.box(), child, pad);
    }
    out[index] = node;
    return sums;
  }

  // The 4-wide tree into `nodes` (resized to fit).
  Sums collapse(std::vector<Bvh4Node>& nodes) {
    nodes.resize(count(0));
    out = nodes.data();
    return emit(0, 0, 1);
  }
};

// The top BVH4_TOP_LEVELS levels moved to the front of the node array in breadth-first order (the
// rest keeps its depth-first order behind them), so that any number of top levels is a prefix: the
// part the PTH walk copies to local memory (kernels/common/accel/bvh4_path.h). Returns the first node of
// each of those depths, then the count of nodes above the deepest (as KD-tree level starts).
std::vector<std::uint32_t> lay_out_top_breadth_first(std::vector<Bvh4Node>& nodes) {
  const auto count = static_cast<std::uint32_t>(nodes.size());
  std::vector<std::uint32_t> order{0};  // the top nodes, breadth first
  std::vector<std::uint32_t> starts{0};
  for (std::uint32_t depth = 1, begin = 0; depth < BVH4_TOP_LEVELS && begin < order.size(); ++depth) {
    const auto end = static_cast<std::uint32_t>(order.size());
    for (std::uint32_t k = begin; k < end; ++k)
      for (const std::uint32_t c : {nodes[order[k]].child.x, nodes[order[k]].child.y, nodes[order[k]].child.z,
                                    nodes[order[k]].child.w})
        if (!bvh4_is_leaf(c)) order.push_back(c);
    starts.push_back(end);
    begin = end;
  }
  if (starts.back() != order.size()) starts.push_back(static_cast<std::uint32_t>(order.size()));
  std::vector<std::uint32_t> moved_to(count, count);
  for (std::uint32_t k = 0; k < order.size(); ++k) moved_to[order[k]] = k;
  std::uint32_t next = static_cast<std::uint32_t>(order.size());
  for (std::uint32_t i = 0; i < count; ++i)
    if (moved_to[i] == count) moved_to[i] = next++;
  std::vector<Bvh4Node> laid_out(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    Bvh4Node n = nodes[i];
    for (std::uint32_t* c : {&n.child.x, &n.child.y, &n.child.z, &n.child.w})
      if (!bvh4_is_leaf(*c)) *c = moved_to[*c];
    laid_out[moved_to[i]] = n;
  }
  nodes = std::move(laid_out);
  return starts;
}

}  // namespace

Bvh4 build_bvh4(std::span<const Triangle> triangles) {
  const auto start = std::chrono::steady_clock::now();
  if (triangles.empty()) throw InputError("a BVH needs at least one triangle");
  if (triangles.size() > BVH4_LEAF_FIRST_MAX)
    throw InputError(fmt::format("the scene has {} triangles; the 4-wide BVH (--tree bvh4) takes at most {}: use "
                                 "--tree deep or compact",
                                 triangles.size(), BVH4_LEAF_FIRST_MAX));
  const binary_bvh::ReferenceChunks references = binary_bvh::make_references(triangles);
  if (references.size > BVH4_LEAF_FIRST_MAX)
    throw InputError(fmt::format("the scene's {} triangles make {} BVH references; the 4-wide BVH (--tree bvh4) "
                                 "takes at most {}: use --tree deep or compact",
                                 triangles.size(), references.size, BVH4_LEAF_FIRST_MAX));
  const binary_bvh::Tree binary = binary_bvh::build(references, kMaxLeaf);
  Bvh4 bvh;
  const Box root = binary.nodes[0].box();
  Collapser collapser{binary, binary.pad()};
  const Collapser::Sums sums = collapser.collapse(bvh.nodes);
  bvh.top_level_starts = lay_out_top_breadth_first(bvh.nodes);
  bvh.leaf_vertices.resize(binary.size);
  binary_bvh::parallel_chunks(binary.size, [&](std::size_t i) {
    const std::uint32_t tri = binary.triangle_of(i);
    bvh.leaf_vertices[i] = triangles[tri];
    bvh.leaf_vertices[i].v0.w = co_as_float(tri);
  });
  bvh.stats.node_count = bvh.nodes.size();
  bvh.stats.references = references.size;
  bvh.stats.leaf_count = sums.leaves;
  bvh.stats.depth = sums.depth;
  bvh.stats.average_leaf_triangles = double(references.size) / double(bvh.stats.leaf_count);
  const float root_area = root.area();
  bvh.stats.sah_cost = root_area > 0 ? sums.sah / root_area : 0.0;
  bvh.stats.bytes = bvh.nodes.size() * sizeof(Bvh4Node) + bvh.leaf_vertices.size() * sizeof(Triangle);
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace cohort
