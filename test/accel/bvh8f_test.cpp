// The 8-wide BVH with float planes' layout (runtime/accel/bvh8f.h): its structure check, and its
// leaves the 4-wide BVH's in fewer nodes. The checks it shares with the other wide BVHs (every ray's
// hit bit for bit against the KD-tree's and the other trees', the same tree for any thread count,
// degenerate inputs) run on it in wide_bvh_common_test.cpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "accel/test_meshes.h"
#include "accel/wide_bvh_check.h"

namespace cohort::test {

// Walks the tree from the root (with StructureTally's checks): each node in depth-first order (each
// node before its children, a lane's subtree after the lanes before it); leaves within
// BVH4_LEAF_MAX; unused lanes BVH4_EMPTY at +infinity (all six planes); reserved words zero; no node
// without children.
std::vector<std::string> structure_errors(const Bvh8f& bvh, const KdTree& kept) {
  StructureTally tally(bvh.nodes.size(), bvh.leaf_vertices, kept);
  std::vector<std::string>& errors = tally.errors;
  std::uint32_t next_in_order = 0;
  std::function<void(std::uint32_t, int, const float*, const float*)> walk = [&](std::uint32_t index, int depth,
                                                                                  const float* plo, const float* phi) {
    if (!tally.reach(index, depth)) return;
    if (index != next_in_order++) errors.push_back(fmt::format("node {} where a depth-first walk has {}", index, next_in_order - 1));
    const Bvh8fNode& n = bvh.nodes[index];
    if (std::any_of(std::begin(n.reserved), std::end(n.reserved), [](std::uint32_t r) { return r != 0; }))
      errors.push_back(fmt::format("node {}: reserved words not zero", index));
    int used = 0;
    for (int lane = 0; lane < 8; ++lane) {
      const std::uint32_t ref = n.child[lane];
      const float lo[3] = {n.planes[0][lane], n.planes[2][lane], n.planes[4][lane]};
      const float hi[3] = {n.planes[1][lane], n.planes[3][lane], n.planes[5][lane]};
      if (ref == BVH4_EMPTY) {
        for (int a = 0; a < 3; ++a)
          if (lo[a] != INFINITY || hi[a] != INFINITY)
            errors.push_back(fmt::format("node {} lane {}: empty lane with a box", index, lane));
        continue;
      }
      ++used;
      tally.box(index, lane, lo, hi, plo, phi);
      if (bvh4_is_leaf(ref))
        tally.leaf(bvh4_leaf_first(ref), bvh4_leaf_count(ref), BVH4_LEAF_MAX, lo, hi);
      else
        walk(ref, depth + 1, lo, hi);
    }
    if (used == 0) errors.push_back(fmt::format("node {} has no children", index));
  };
  walk(0, 1, nullptr, nullptr);
  return tally.finish(bvh.stats, BVH4_MAX_DEPTH);
}

namespace {

// The same binary tree collapsed at width 8 holds the same leaves as the 4-wide BVH's (the same
// leaf entries in the same order) in fewer nodes.
TEST(Bvh8f, HasTheFourWideLeavesInFewerNodes) {
  const KdTree kept = kept_triangles(random_soup(20'000, 5));
  const Bvh8f wide = build_bvh8f(kept.triangles);
  const Bvh4 narrow = build_bvh4(kept.triangles);
  ASSERT_EQ(wide.leaf_vertices.size(), narrow.leaf_vertices.size());
  EXPECT_EQ(0, std::memcmp(wide.leaf_vertices.data(), narrow.leaf_vertices.data(),
                           wide.leaf_vertices.size() * sizeof(Triangle)));
  EXPECT_EQ(wide.stats.leaf_count, narrow.stats.leaf_count);
  EXPECT_LT(wide.stats.node_count, narrow.stats.node_count * 3 / 4);  // 0.64x on this soup
  EXPECT_LT(wide.stats.depth, narrow.stats.depth);
}

}  // namespace
}  // namespace cohort::test
