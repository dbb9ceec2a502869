// The 4-wide BVH's layout (runtime/accel/bvh4.h): its structure check. The checks it shares with
// the other wide BVHs (every ray's hit bit for bit against the KD-tree's and the other trees', the
// same tree for any thread count, degenerate inputs) run on it in wide_bvh_common_test.cpp.
#include <fmt/format.h>

#include <bit>
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

// The step GPUs take (bvh4_descend_sorted: every mask through the sorting network, pushes by count)
// against the CPUs' (bvh4_descend, which takes one or two entered children without it): for every
// mask and entry distances with ties, the same child goes on and the same children are pushed in the
// same order, so both walks visit the same nodes in the same order.
TEST(Bvh4, SortedDescendIsTheBranchingOneForEveryMask) {
  std::vector<Bvh4Node> nodes(4);  // the children's references point here (the host's prefetch reads nothing)
  Bvh4View view{};
  view.nodes = nodes.data();
  const float values[] = {0.0f, 1.0f, 1.0f, 2.5f, -0.0f, 7.0f};
  int cases = 0;
  for (std::uint32_t mask = 1; mask < 16; ++mask)
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        for (int c = 0; c < 6; ++c) {
          const co_float4 enter = {values[a], values[b], values[c], values[(a + b + c) % 6]};
          const co_uint4 child = {0u, 1u, 2u, 3u};
          std::uint32_t ref[2] = {9u, 9u};
          float ref_t[2] = {-1.0f, -1.0f};
          std::uint32_t stack_ref[2][8] = {};
          float stack_t[2][8] = {};
          int sp[2] = {1, 1};  // an entry below, untouched by both
          bvh4_descend(&view, mask, enter, child, &ref[0], &ref_t[0], stack_ref[0], stack_t[0], &sp[0]);
          bvh4_descend_sorted(&view, mask, enter, child, &ref[1], &ref_t[1], stack_ref[1], stack_t[1], &sp[1]);
          const std::string what = fmt::format("mask {:x}, entries {} {} {} {}", mask, enter.x, enter.y, enter.z, enter.w);
          ASSERT_EQ(ref[0], ref[1]) << what;
          ASSERT_EQ(std::bit_cast<std::uint32_t>(ref_t[0]), std::bit_cast<std::uint32_t>(ref_t[1])) << what;
          ASSERT_EQ(sp[0], sp[1]) << what;
          ASSERT_EQ(sp[0], 1 + std::popcount(mask) - 1) << what;
          for (int i = 1; i < sp[0]; ++i) {
            ASSERT_EQ(stack_ref[0][i], stack_ref[1][i]) << what << ", entry " << i;
            ASSERT_EQ(std::bit_cast<std::uint32_t>(stack_t[0][i]), std::bit_cast<std::uint32_t>(stack_t[1][i]))
                << what << ", entry " << i;
          }
          ++cases;
        }
  EXPECT_EQ(cases, 15 * 216);
}

}  // namespace cohort::test
