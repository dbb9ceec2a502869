// build_bvh4: the binary BVH of runtime/accel/binary_bvh.h collapsed into 4-wide nodes depth first
// (runtime/accel/wide_collapse.h).
#include "runtime/accel/bvh4.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>

#include "kernels/common/accel/bvh4_traverse.h"
#include "runtime/accel/binary_bvh.h"
#include "runtime/accel/wide_collapse.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

using binary_bvh::Box;
using Collapser = wide_collapse::Collapser<Bvh4Node, 4>;

constexpr std::uint32_t kMaxLeaf = 4;  // triangles; BVH4_LEAF_MAX allows up to 16
static_assert(binary_bvh::kMaxDepth <= BVH4_MAX_DEPTH, "the traversal stack must hold the deepest tree");


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
