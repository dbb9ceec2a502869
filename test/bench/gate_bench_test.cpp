// `cohort bench --gate`: every order traces the same rays to the same hits, waves shrink by the rays
// that miss, and the orders come with their sort cost.
#include <gtest/gtest.h>

#include <filesystem>

#include "runtime/bench/gate_bench.h"
#include "runtime/backend/open_device.h"

using namespace cohort;

class GateBench : public ::testing::TestWithParam<const char*> {};

// On the KD-tree (the paper's PTH bits) and on the BVH the renderer traces (its first-path bits).
TEST_P(GateBench, EveryOrderFindsTheSameHitsAndHasASortCost) {
  const PreparedScene scene =
      prepare_scene(std::filesystem::path(COHORT_SOURCE_DIR) / "scenes/cornell-box.gltf", tree_options(GetParam()));
  ASSERT_STREQ(scene.tree_kind(), GetParam());
  const auto device = open_device(Backend::opencl, "");
  const ProgramCache cache(ProgramCache::default_directory());
  GateOptions options;
  options.res = 48;
  options.bounces = 3;
  // the file's camera looks into the open box (the protocol camera sees its outside, where every
  // diffuse ray escapes)
  const auto bounces = gate_bench(*device, cache, scene, scene.camera, options);
  ASSERT_EQ(bounces.size(), 3u);
  EXPECT_EQ(bounces[0].rays, 48u * 48u);
  for (std::size_t b = 0; b < bounces.size(); ++b) {
    EXPECT_TRUE(bounces[b].hits_agree) << "bounce " << bounces[b].bounce;
    if (b > 0) {
      EXPECT_LE(bounces[b].rays, bounces[b - 1].rays);  // rays that missed left the wave
      EXPECT_GT(bounces[b].rays, 0u);
    }
    ASSERT_EQ(bounces[b].orders.size(), 8u);
    EXPECT_EQ(bounces[b].orders[0].name, "generation");
    for (const GateOrder& o : bounces[b].orders) {
      EXPECT_EQ(o.rays_per_second.runs.size(), 3u) << o.name;
      EXPECT_GT(o.rays_per_second.median(), 0.0) << o.name;
      if (o.key_bits) {
        EXPECT_GT(o.sort_ms, 0.0) << o.name;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Trees, GateBench, ::testing::Values("deep", "bvh4"));
