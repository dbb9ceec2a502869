// Structural invariants of the device layout and the builder's options.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <limits>
#include <stdexcept>

#include "accel/test_meshes.h"
#include "accel/tree_check.h"
#include "runtime/accel/kdtree/subtree.h"

namespace cohort::test {
namespace {

void expect_valid(const KdTree& tree, const KdBuildOptions& options = {}) {
  const int max_depth = kd::effective_max_depth(options, tree.triangles.size());
  for (const std::string& e : layout_errors(tree, max_depth)) ADD_FAILURE() << e;
  for (const std::string& e : coverage_errors(tree)) ADD_FAILURE() << e;
}

TEST(KdTreeStructure, SoupIsValid) {
  const KdTree tree = build_kdtree(random_soup(3000, 3));
  EXPECT_GT(tree.nodes.size(), 100u);
  EXPECT_LT(tree.stats.sah_cost, 1.5 * tree.triangles.size()) << "better than one big leaf";
  expect_valid(tree);
}

TEST(KdTreeStructure, SharedModelsAreValid) {
  for (const char* model :
       {"bunny/bun_zipper_res4.ply", "cornell-box-mcguire/CornellBox-Original.obj",
        "cornell-box-mcguire/CornellBox-Sphere.obj"}) {
    const auto positions = load_shared(model);
    if (!positions) GTEST_SKIP() << "shared scenes not found";
    SCOPED_TRACE(model);
    const KdTree tree = build_kdtree(*positions);
    fmt::print("[{}] {}\n", model, summary(tree));
    expect_valid(tree);
  }
}

TEST(KdTreeStructure, DefaultDepthLimitFollowsTriangleCount) {
  EXPECT_EQ(kd::effective_max_depth({}, 1), 8);
  EXPECT_EQ(kd::effective_max_depth({}, 1024), 8 + 18);
  EXPECT_EQ(kd::effective_max_depth({}, std::size_t{1} << 29), kd::kDepthCap);
  KdBuildOptions deep;
  deep.max_depth = 100;
  EXPECT_EQ(kd::effective_max_depth(deep, 10), kd::kDepthCap);
  EXPECT_LE(kd::kDepthCap, KD_MAX_DEPTH);
}

TEST(KdTreeStructure, MaxDepthIsHonoured) {
  KdBuildOptions options;
  options.max_depth = 5;
  const KdTree tree = build_kdtree(random_soup(3000, 4), options);
  EXPECT_LE(tree.stats.depth, 5);
  expect_valid(tree, options);
  options.max_depth = 0;
  options.parallel = false;
  options.leaf_triangles = 1'000'000;
  const KdTree one_leaf = build_kdtree(random_soup(3000, 4), options);
  EXPECT_EQ(one_leaf.nodes.size(), 1u);
  EXPECT_EQ(one_leaf.stats.leaf_references, 3000u);
}

TEST(KdTreeStructure, SplitIsStoredAsFloatBits) {
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {9, 0, 0}, {10, 0, 0}, {9, 1, 0}};
  const KdTree tree = build_kdtree(p);
  ASSERT_EQ(tree.nodes.size(), 3u);
  EXPECT_EQ(kd_axis(tree.nodes[0]), 0u);
  const float split = co_as_float(tree.nodes[0].word1);
  EXPECT_GE(split, 1.f);
  EXPECT_LE(split, 9.f);
  EXPECT_EQ(kd_left_child(tree.nodes[0]), 1u);
  EXPECT_EQ(kd_leaf_count(tree.nodes[1]), 1u);
  EXPECT_EQ(kd_leaf_count(tree.nodes[2]), 1u);
}

// The intermediate node packs what the device layout holds: a leaf of up to KD_MAX_INDEX
// references anywhere in 32-bit leaf lists, any split bits, and right children or spawned slots up
// to its limit, none of the fields spilling into another.
TEST(KdTreeStructure, BuildNodeKeepsEveryField) {
  static_assert(kd::BuildNode::kMaxCount == KD_MAX_INDEX);
  const kd::BuildNode leaf = kd::BuildNode::leaf(KD_MAX_INDEX, 0xFFFFFFFFu);
  EXPECT_TRUE(leaf.is_leaf());
  EXPECT_EQ(leaf.count(), KD_MAX_INDEX);
  EXPECT_EQ(leaf.first(), 0xFFFFFFFFu);
  for (int axis = 0; axis < 3; ++axis) {
    for (const float split : {-0.f, 1.f / 3.f, -std::numeric_limits<float>::max()}) {
      kd::BuildNode inner = kd::BuildNode::inner(axis, split);
      EXPECT_FALSE(inner.is_leaf());
      inner.set_right(kd::BuildNode::kMaxIndex);
      EXPECT_EQ(inner.axis(), static_cast<std::uint32_t>(axis));
      EXPECT_FALSE(inner.spawned());
      EXPECT_EQ(inner.index(), kd::BuildNode::kMaxIndex);
      EXPECT_EQ(std::bit_cast<std::uint32_t>(inner.split()), std::bit_cast<std::uint32_t>(split));
      inner.set_spawned(kd::BuildNode::kMaxIndex - 1);
      EXPECT_EQ(inner.axis(), static_cast<std::uint32_t>(axis));
      EXPECT_TRUE(inner.spawned());
      EXPECT_EQ(inner.index(), kd::BuildNode::kMaxIndex - 1);
      inner.set_right(7);
      EXPECT_FALSE(inner.spawned());
      EXPECT_EQ(inner.index(), 7u);
      EXPECT_FALSE(inner.is_leaf());
    }
  }
}

TEST(KdTreeStructure, StatsAddUp) {
  const KdTree tree = build_kdtree(random_soup(2000, 5));
  const KdTreeStats& s = tree.stats;
  EXPECT_EQ(s.node_count, 2 * s.leaf_count - 1);
  EXPECT_EQ(s.leaf_references, tree.leaf_triangles.size());
  EXPECT_NEAR(s.average_leaf_triangles,
              double(s.leaf_references) / double(s.leaf_count - s.empty_leaf_count), 1e-9);
  EXPECT_EQ(s.bytes,
            8 * tree.nodes.size() + 4 * tree.leaf_triangles.size() + 48 * tree.triangles.size());
  EXPECT_GT(s.build_seconds, 0.0);
  EXPECT_GT(s.sah_cost, 0.0);
}

}  // namespace
}  // namespace cohort::test
