// The fast build's planes against the exact sweep: binned candidates with the exact sweep inside
// the best bins must keep the tree's SAH cost within 2% of the all-exact build (Wald & Havran's
// tree), and must still find a plane that cuts off empty space exactly at a triangle boundary.
#include <gtest/gtest.h>

#include <climits>

#include "accel/test_meshes.h"
#include "accel/tree_check.h"
#include "runtime/accel/kdtree_internal.h"
#include "runtime/util/error.h"

namespace cohort::test {
namespace {

KdBuildOptions exact_everywhere() {
  KdBuildOptions options;
  options.exact_triangles = INT_MAX;
  return options;
}

void expect_sah_close(const std::vector<glm::vec3>& positions, const char* what) {
  SCOPED_TRACE(what);
  const KdTree fast = build_kdtree(positions);
  const KdTree exact = build_kdtree(positions, exact_everywhere());
  EXPECT_LE(fast.stats.sah_cost, 1.02 * exact.stats.sah_cost)
      << "fast " << summary(fast) << "\nexact " << summary(exact);
  for (const std::string& e : layout_errors(fast, KD_MAX_DEPTH)) ADD_FAILURE() << e;
}

TEST(KdTreeQuality, FastBuildSahWithinTwoPercentOfExact) {
  // Large enough that the top levels are binned (above exact_triangles references).
  expect_sah_close(random_soup(20'000, 8), "soup");
  if (const auto bunny = load_shared("bunny/bun_zipper_res2.ply")) {
    expect_sah_close(*bunny, "bunny res2");
  }
}

TEST(KdTreeQuality, BinnedSearchCutsOffEmptySpaceAtTheGeometry) {
  // 2000 small triangles with x in [0.05, 0.3] inside the cell [0, 1]^3: the best plane cuts the
  // empty right side off exactly at x = 0.3, which is no bin boundary (bins of 1/8).
  std::vector<kd::Ref> refs;
  for (std::uint32_t i = 0; i < 2000; ++i) {
    const float y = 0.0005f * static_cast<float>(i);
    Bounds box;
    box.extend(glm::vec3(0.05f, y, 0.2f));
    box.extend(glm::vec3(0.3f, y + 0.0004f, 0.8f));
    refs.push_back({box, i});
  }
  Bounds cell;
  cell.extend(glm::vec3(0.f));
  cell.extend(glm::vec3(1.f));
  kd::SahContext context{};
  ASSERT_TRUE(kd::make_sah_context(cell, refs.size(), KdBuildOptions{}, context));
  kd::PlaneScratch scratch;
  const kd::SplitPlane plane = kd::find_binned_plane(context, refs, 8, false, scratch);
  ASSERT_TRUE(plane.valid());
  EXPECT_EQ(plane.axis, 0);
  EXPECT_EQ(plane.pos, 0.3f);
  EXPECT_EQ(plane.left_count, 2000u);
  EXPECT_EQ(plane.right_count, 0u);
}

TEST(KdTreeQuality, BudgetLowersTheDepthUntilTheTreeFits) {
  const std::vector<glm::vec3> p = random_soup(5'000, 9);
  const KdTree full = build_kdtree(p);
  const std::size_t budget = full.stats.bytes * 8 / 10;
  const KdTree fitted = build_kdtree_within(p, {}, budget);
  EXPECT_LE(fitted.stats.bytes, budget);
  EXPECT_LT(fitted.stats.depth, full.stats.depth);
  EXPECT_GT(fitted.stats.bytes, full.stats.bytes / 2) << "the deepest tree that fits, not any";
  for (const std::string& e : layout_errors(fitted, KD_MAX_DEPTH)) ADD_FAILURE() << e;
  for (const std::string& e : coverage_errors(fitted)) ADD_FAILURE() << e;
  EXPECT_EQ(build_kdtree_within(p, {}, full.stats.bytes).stats.bytes, full.stats.bytes);
  EXPECT_THROW(build_kdtree_within(p, {}, 1000), InputError);
}

}  // namespace
}  // namespace cohort::test
