// What every wide BVH (the 4-wide one, the compressed 8-wide one, the 8-wide one with float planes)
// must do alike, one typed suite over their traits (accel/wide_bvh_check.h): for every ray the
// KD-tree's, every other tree's and brute force's hit bit for bit, also at shared edges and vertices;
// the same tree for any thread count; sound shallow trees and the lowest index's hit on degenerate
// inputs; a miss for a NaN direction; an error for no triangles. What only one layout has is in its
// own file (bvh4_test.cpp, bvh8_test.cpp, bvh8f_test.cpp), its structure check among it.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include "accel/test_meshes.h"
#include "accel/wide_bvh_check.h"
#include "runtime/util/error.h"

namespace cohort::test {
namespace {

template <typename Traits>
class WideBvh : public ::testing::Test {};

// No name generator: ctest's discovery (gtest_discover_tests) names a typed test by its type only
// when gtest numbers the types, as WideBvh.GivesEveryTreesHitsBitForBit<cohort::test::Bvh4Traits>.
using WideBvhTraits = ::testing::Types<Bvh4Traits, Bvh8Traits, Bvh8fTraits>;
TYPED_TEST_SUITE(WideBvh, WideBvhTraits);

TYPED_TEST(WideBvh, GivesEveryTreesHitsBitForBit) {
  expect_same_hits<TypeParam>(coplanar_grid(100, 100), "20k coplanar");
  expect_same_hits<TypeParam>(random_soup(4000, 7), "soup");
  expect_same_hits<TypeParam>(load_shipped("voxel-terrain.gltf"), "voxel terrain");
  for (const char* model : {"bunny/bun_zipper_res2.ply", "cornell-box-mcguire/CornellBox-Original.obj"})
    if (const auto positions = load_shared(model)) expect_same_hits<TypeParam>(*positions, model);
}

TYPED_TEST(WideBvh, SameTreeForAnyThreadCount) {
  const KdTree kept = kept_triangles(random_soup(20'000, 3));
  const typename TypeParam::Tree many = TypeParam::build(kept.triangles);
  tbb::task_arena one(1);
  const typename TypeParam::Tree single = one.execute([&] { return TypeParam::build(kept.triangles); });
  ASSERT_EQ(many.nodes.size(), single.nodes.size());
  EXPECT_EQ(0, std::memcmp(many.nodes.data(), single.nodes.data(), many.nodes.size() * sizeof(many.nodes[0])));
  ASSERT_EQ(leaf_bytes(many).size(), leaf_bytes(single).size());
  EXPECT_EQ(0, std::memcmp(leaf_bytes(many).data(), leaf_bytes(single).data(), leaf_bytes(many).size()));
  EXPECT_TRUE(structure_errors(many, kept).empty());
  // the statistics are summed per subtree and joined in lane order: the same figures too
  EXPECT_EQ(many.stats.sah_cost, single.stats.sah_cost);
  EXPECT_EQ(many.stats.leaf_count, single.stats.leaf_count);
  EXPECT_EQ(many.stats.depth, single.stats.depth);
}

// Where a binned build has nothing to bin: one triangle; 1000 copies of one triangle (every centroid
// in one point); triangles whose centroids halve their distance each time (each SAH split peels off
// one, which the object-median fallback must stop before the stack depth). Sound shallow trees, and
// through the copies the first copy's hit (the least index at equal t); in the 8-wide BVH with float
// planes through a node whose eight lanes all enter at the same distance (the stack's insertion at
// equal keys).
TYPED_TEST(WideBvh, DegenerateInputsStayShallowAndFindTheLowestIndex) {
  const std::vector<glm::vec3> one{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  std::vector<glm::vec3> copies, halving;
  for (int i = 0; i < 1000; ++i) copies.insert(copies.end(), one.begin(), one.end());
  for (int i = 0; i < 300; ++i) {
    const float x = std::ldexp(1.0f, -i / 3);  // tiny triangles at x = 2^-k, then 2^-(k+1), ...
    const float s = std::ldexp(1.0f, -i / 3 - 8);
    halving.insert(halving.end(), {{x, 0, float(i % 3)}, {x + s, 0, float(i % 3)}, {x, s, float(i % 3)}});
  }
  for (const std::vector<glm::vec3>* positions : std::array<const std::vector<glm::vec3>*, 3>{&one, &copies, &halving}) {
    const KdTree kept = kept_triangles(*positions);
    const typename TypeParam::Tree bvh = TypeParam::build(kept.triangles);
    for (const std::string& e : structure_errors(bvh, kept)) ADD_FAILURE() << e;
    EXPECT_LE(bvh.stats.depth, TypeParam::kMaxDepth);
  }
  const KdTree kept = kept_triangles(copies);
  const BuiltBvh<TypeParam> bvh(kept.triangles);
  const HitOut hit = bvh.trace(v3(0.2f, 0.2f, 0.f), v3(0.f, 0.f, 1.f), kInf, 0);
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_EQ(hit.t, 1.0f);
}

// A ray whose direction has a NaN component (nothing the renderer should make, but a degenerate
// input can) misses, closest or any hit, instead of walking out of the arrays (the trees share
// bvh4_inverse).
TYPED_TEST(WideBvh, ARayWithANanDirectionMisses) {
  const KdTree kept = kept_triangles(random_soup(4000, 7));  // a soup around the origin
  const BuiltBvh<TypeParam> bvh(kept.triangles);
  EXPECT_NE(bvh.trace(v3(0.f, 0.f, 0.f), v3(0.f, 0.f, 1.f), kInf, 0).triangle, HIT_NONE);
  const float nan = std::nanf("");
  for (const co_vec3 dir : {v3(nan, 0.f, 1.f), v3(0.f, nan, 0.f), v3(nan, nan, nan), v3(0.3f, -0.2f, nan)})
    for (const int any_hit : {0, 1}) EXPECT_EQ(bvh.trace(v3(0.f, 0.f, 0.f), dir, kInf, any_hit).triangle, HIT_NONE);
}

// An origin that is not finite hits nothing and stays in the tree: NaN slabs entered every lane of a
// node, the unused ones too, and the walk read past the leaf array (a crash on the host).
TYPED_TEST(WideBvh, ARayWithANonFiniteOriginMisses) {
  const KdTree kept = kept_triangles(random_soup(4000, 7));
  const BuiltBvh<TypeParam> bvh(kept.triangles);
  const float nan = std::nanf("");
  for (const co_vec3 org : {v3(nan, 0.f, 0.f), v3(0.f, nan, 0.f), v3(0.f, 0.f, nan), v3(nan, nan, nan),
                            v3(kInf, 0.f, 0.f), v3(-kInf, kInf, -kInf), v3(nan, -kInf, 0.f)})
    for (const int any_hit : {0, 1}) EXPECT_EQ(bvh.trace(org, v3(0.3f, -0.2f, 0.9f), kInf, any_hit).triangle, HIT_NONE);
}

TYPED_TEST(WideBvh, RejectsAnEmptyInput) {
  EXPECT_THROW(TypeParam::build({}), InputError);
}

}  // namespace
}  // namespace cohort::test
