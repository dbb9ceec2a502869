// build_bvh4: the binary BVH of runtime/accel/binary_bvh.h collapsed into 4-wide nodes depth first
// (runtime/accel/wide_collapse.h).
#include "runtime/accel/bvh4.h"

#include <chrono>
#include <vector>

#include "kernels/common/accel/bvh4_traverse.h"
#include "runtime/accel/wide_collapse.h"

namespace cohort {
namespace {

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
  Bvh4 bvh;
  wide_collapse::build<4>(bvh, triangles, "4-wide BVH (--tree bvh4)");
  bvh.top_level_starts = lay_out_top_breadth_first(bvh.nodes);
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace cohort
