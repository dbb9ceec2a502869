// The test-only readers stay usable as the fallback of load_shared().
#include "accel/test_meshes.h"

#include <gtest/gtest.h>

namespace cohort::test {
namespace {

TEST(TestMeshes, FallbackReadersReadTheSharedModels) {
  const auto root = shared_scenes();
  if (!root) GTEST_SKIP() << "shared scenes not found";
  EXPECT_EQ(read_ascii_ply(*root / "bunny/bun_zipper_res2.ply").size(), 3u * 16301);
  EXPECT_EQ(read_obj(*root / "cornell-box-mcguire/CornellBox-Original.obj").size(), 3u * 36);
}

TEST(TestMeshes, GeneratorsMakeWhatTheySay) {
  EXPECT_EQ(random_soup(100, 1).size(), 300u);
  EXPECT_EQ(coplanar_grid(3, 2).size(), 3u * 12);
  EXPECT_EQ(triangle_copies(5).size(), 15u);
}

}  // namespace
}  // namespace cohort::test
