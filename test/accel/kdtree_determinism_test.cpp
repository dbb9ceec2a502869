// The tree is the same bits whatever the thread timing, and the same with and without TBB.
#include <gtest/gtest.h>

#include <cstring>

#include "accel/test_meshes.h"
#include "runtime/accel/kdtree.h"

namespace cohort::test {
namespace {

bool same_nodes(const std::vector<KdNode>& a, const std::vector<KdNode>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(KdNode)) == 0;
}

TEST(KdTreeDeterminism, ParallelBuildsAreIdentical) {
  // Large enough for many parallel subtrees (the builder forks above 4K triangles).
  const std::vector<glm::vec3> p = random_soup(50'000, 21);
  const KdTree first = build_kdtree(p);
  const KdTree second = build_kdtree(p);
  KdBuildOptions serial;
  serial.parallel = false;
  const KdTree third = build_kdtree(p, serial);
  EXPECT_GT(first.nodes.size(), 10'000u);
  EXPECT_TRUE(same_nodes(first.nodes, second.nodes));
  EXPECT_EQ(first.leaf_triangles, second.leaf_triangles);
  EXPECT_TRUE(same_nodes(first.nodes, third.nodes)) << "serial and parallel builds differ";
  EXPECT_EQ(first.leaf_triangles, third.leaf_triangles);
}

}  // namespace
}  // namespace cohort::test
