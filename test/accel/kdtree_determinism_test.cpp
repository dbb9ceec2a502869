// The tree is the same bits whatever the thread count and timing, and the same with and without
// TBB.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <span>

#include "accel/test_meshes.h"
#include "runtime/accel/kdtree/kdtree.h"

namespace cohort::test {
namespace {

bool same_nodes(std::span<const KdNode> a, std::span<const KdNode> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(KdNode)) == 0;
}

void expect_same(const KdTree& a, const KdTree& b, const char* what) {
  EXPECT_TRUE(same_nodes(a.nodes, b.nodes)) << what;
  EXPECT_EQ(a.leaf_triangles, b.leaf_triangles) << what;
}

TEST(KdTreeDeterminism, ParallelBuildsAreIdentical) {
  // Large enough for parallel subtrees (above 4K references), parallel binning (above 32K) and a
  // root split in parallel chunks (above 64K).
  const std::vector<glm::vec3> p = random_soup(70'000, 21);
  const KdTree first = build_kdtree(p);
  EXPECT_GT(first.nodes.size(), 10'000u);
  expect_same(first, build_kdtree(p), "two parallel builds differ");
  KdBuildOptions serial;
  serial.parallel = false;
  expect_same(first, build_kdtree(p, serial), "serial and parallel builds differ");
  for (int threads : {1, 8}) {
    tbb::task_arena arena(threads);
    const KdTree t = arena.execute([&] { return build_kdtree(p); });
    expect_same(first, t, "a build on another thread count differs");
  }
}

}  // namespace
}  // namespace cohort::test
