// The 4-wide BVH's layout (runtime/accel/bvh4.h): its structure check. The checks it shares with
// the other wide BVHs (every ray's hit bit for bit against the KD-tree's and the other trees', the
// same tree for any thread count, degenerate inputs) run on it in wide_bvh_common_test.cpp.
#include <fmt/format.h>

#include <cmath>
#include <functional>

#include "accel/wide_bvh_check.h"

namespace cohort::test {

// Walks the tree (with StructureTally's checks): the top levels breadth first, each depth a range
// of top_level_starts, the rest depth first (each node before its children, a lane's subtree after
// the lanes before it); leaves within BVH4_LEAF_MAX; unused lanes BVH4_EMPTY at +infinity; reserved
// words zero.
std::vector<std::string> structure_errors(const Bvh4& bvh, const KdTree& kept) {
  StructureTally tally(bvh.nodes.size(), bvh.leaf_vertices, kept);
  std::vector<std::string>& errors = tally.errors;
  const auto& starts = bvh.top_level_starts;
  std::uint32_t next_in_order = starts.empty() ? 0 : starts.back();
  std::function<void(std::uint32_t, int, const float*, const float*)> walk = [&](std::uint32_t index, int depth,
                                                                                  const float* plo, const float* phi) {
    if (!tally.reach(index, depth)) return;
    if (std::size_t(depth) < starts.size()) {
      if (index < starts[depth - 1] || index >= starts[depth])
        errors.push_back(fmt::format("node {} at depth {} outside the top's range for it", index, depth));
    } else if (index != next_in_order++) {
      errors.push_back(fmt::format("node {} where a depth-first walk has {}", index, next_in_order - 1));
    }
    const Bvh4Node& n = bvh.nodes[index];
    if (n.reserved.x || n.reserved.y || n.reserved.z || n.reserved.w) errors.push_back("reserved words not zero");
    for (int lane = 0; lane < 4; ++lane) {
      const std::uint32_t ref = (&n.child.x)[lane];
      const float lo[3] = {(&n.lo_x.x)[lane], (&n.lo_y.x)[lane], (&n.lo_z.x)[lane]};
      const float hi[3] = {(&n.hi_x.x)[lane], (&n.hi_y.x)[lane], (&n.hi_z.x)[lane]};
      if (ref == BVH4_EMPTY) {
        if (lo[0] != INFINITY || hi[0] != INFINITY) errors.push_back(fmt::format("node {} lane {}: empty lane with a box", index, lane));
        continue;
      }
      tally.box(index, lane, lo, hi, plo, phi);
      if (bvh4_is_leaf(ref))
        tally.leaf(bvh4_leaf_first(ref), bvh4_leaf_count(ref), BVH4_LEAF_MAX, lo, hi);
      else
        walk(ref, depth + 1, lo, hi);
    }
  };
  walk(0, 1, nullptr, nullptr);
  return tally.finish(bvh.stats, BVH4_MAX_DEPTH);
}

}  // namespace cohort::test
