// The collapse of the binary SAH tree into wide nodes (runtime/accel/wide_collapse.h) with
// least_sah, which the CPU's 8-wide BVH takes, picks each wide node's lanes to minimise the tree's
// SAH: on small and mid-sized trees its SAH is the least over every way of choosing the lanes,
// enumerated here set by set (a cut of each subtree into at most Width lanes), independently of the
// collapse's own recursion over lane budgets.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "accel/test_meshes.h"
#include "accel/tree_check.h"
#include "runtime/accel/bvh8f.h"
#include "runtime/accel/wide_collapse.h"

namespace cohort::test {
namespace {

template <int Width>
class BruteForceCollapse {
 public:
  BruteForceCollapse(const binary_bvh::Tree& tree, binary_bvh::LeafShape shape) : b_(tree), shape_(shape) {}

  // The least SAH sum of the wide tree rooted at binary node `slot`.
  double best_tree(std::uint32_t slot) {
    const binary_bvh::Node& x = b_.nodes[slot];
    if (x.count) return lane_cost(slot);  // a root that is a leaf: one lane, no node
    double best = std::numeric_limits<double>::infinity();
    for (const Cut& left : cuts(x.left, Width - 1))
      for (const Cut& right : cuts(x.right, Width - int(left.size()))) best = std::min(best, cost(left) + cost(right));
    return binary_bvh::kNodeCost * double(x.box().area()) + best;
  }

 private:
  using Cut = std::vector<std::uint32_t>;  // the binary nodes that become lanes

  // Every set of at most `limit` binary nodes that covers subtree `slot` (each leaf under exactly one).
  std::vector<Cut> cuts(std::uint32_t slot, int limit) const {
    std::vector<Cut> out{{slot}};
    const binary_bvh::Node& x = b_.nodes[slot];
    if (x.count || limit < 2) return out;
    for (const Cut& left : cuts(x.left, limit - 1))
      for (Cut right : cuts(x.right, limit - int(left.size()))) {
        right.insert(right.end(), left.begin(), left.end());
        out.push_back(right);
      }
    return out;
  }

  double cost(const Cut& lanes) {
    double sum = 0.0;
    for (const std::uint32_t lane : lanes) sum += lane_cost(lane);
    return sum;
  }

  // A lane's cost: a leaf's tests, or the best wide tree under an inner node.
  double lane_cost(std::uint32_t slot) {
    const binary_bvh::Node& x = b_.nodes[slot];
    if (x.count) return double(x.box().area()) * shape_.tests(x.count);
    const auto known = memo_.find(slot);
    if (known != memo_.end()) return known->second;
    return memo_[slot] = best_tree(slot);
  }

  const binary_bvh::Tree& b_;
  binary_bvh::LeafShape shape_;
  std::map<std::uint32_t, double> memo_;
};

template <class WideNode, int Width>
void expect_least_sah(const std::vector<glm::vec3>& positions, binary_bvh::LeafShape shape, const std::string& name) {
  const KdTree kept = kept_triangles(positions);
  const binary_bvh::Tree binary = binary_bvh::build(binary_bvh::make_references(kept.triangles), kept.triangles, shape);
  wide_collapse::Collapser<WideNode, Width> collapser{binary, binary.pad()};
  collapser.shape = shape;
  collapser.least_sah = true;
  std::vector<WideNode> nodes;
  const double sah = collapser.collapse(nodes).sah;
  const double least = BruteForceCollapse<Width>(binary, shape).best_tree(0);
  EXPECT_NEAR(sah, least, 1e-6 * least) << Width << " wide, " << name;
}

// Long thin triangles across the whole box, each near one of three directions: children's boxes
// overlap their parent's almost wholly, so opening a node often costs more than it saves.
std::vector<glm::vec3> crossing_sticks(std::size_t count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  std::vector<glm::vec3> out;
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3 a(unit(rng), unit(rng), unit(rng));
    glm::vec3 b = -a;
    b[i % 3] = unit(rng);
    out.insert(out.end(), {a, b, b + 0.01f * glm::vec3(unit(rng), unit(rng), unit(rng))});
  }
  return out;
}

// Random soups of a few to thousands of triangles, and meshes with structure (a grid of coplanar
// cells, crossing sticks, the voxel terrain, a scanned model where the shared scenes are there). A cut
// of at most j lanes opens at most j - 1 nodes below its root, so there are few of them whatever the
// subtree's size, and the enumeration stays quick on trees of thousands of triangles.
template <class WideNode, int Width>
void expect_least_sah(binary_bvh::LeafShape shape, std::initializer_list<std::size_t> soup_sizes) {
  for (const std::uint32_t seed : {1u, 2u, 3u})
    for (const std::size_t count : soup_sizes)
      expect_least_sah<WideNode, Width>(random_soup(count, seed), shape,
                                        fmt::format("{} random triangles, seed {}", count, seed));
  expect_least_sah<WideNode, Width>(coplanar_grid(30, 30), shape, "coplanar grid");
  expect_least_sah<WideNode, Width>(crossing_sticks(3'000), shape, "crossing sticks");
  expect_least_sah<WideNode, Width>(load_shipped("voxel-terrain.gltf"), shape, "voxel terrain");
  if (const auto bunny = load_shared("bunny/bun_zipper_res2.ply"))
    expect_least_sah<WideNode, Width>(*bunny, shape, "bunny res2");
}

TEST(WideCollapse, FourWideLanesGiveTheLeastSah) {
  expect_least_sah<Bvh4Node, 4>(binary_bvh::LeafShape{wide_collapse::kMaxLeaf}, {9, 90, 2'000, 20'000});
}

// build_bvh8f (the default tree on CPUs) is built that way: its SAH figure is the least.
TEST(WideCollapse, TheCpuTreeHasTheLeastSah) {
  const KdTree kept = kept_triangles(random_soup(2'000, 4));
  const binary_bvh::LeafShape shape{wide_collapse::kMaxLeaf, 4u, 0.125f};
  const binary_bvh::Tree binary = binary_bvh::build(binary_bvh::make_references(kept.triangles), kept.triangles, shape);
  const double least = BruteForceCollapse<8>(binary, shape).best_tree(0) / double(binary.nodes[0].box().area());
  EXPECT_NEAR(build_bvh8f(kept.triangles).stats.sah_cost, least, 1e-6 * least);
}

// The binary tree's SAH cost over its root's area (a node kNodeCost, a leaf its tests).
double binary_sah(const binary_bvh::Tree& tree, binary_bvh::LeafShape shape) {
  double sum = 0;
  std::vector<std::uint32_t> stack{0u};
  while (!stack.empty()) {
    const binary_bvh::Node& n = tree.nodes[stack.back()];
    stack.pop_back();
    if (n.count) {
      sum += double(n.box().area()) * shape.tests(n.count);
    } else {
      sum += binary_bvh::kNodeCost * double(n.box().area());
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  return sum / double(tree.nodes[0].box().area());
}

// Spatial splits (binary_bvh.cpp) cut long triangles whose boxes overlap: on crossing sticks the
// tree's SAH cost falls below the object splits' alone (0.92x), on a random soup it is no higher
// (0.997x), for at most a quarter more references; where nothing overlaps (a grid of cells) they
// add none.
TEST(BinaryBvh, SpatialSplitsLowerTheSahWhereBoxesOverlap) {
  const binary_bvh::LeafShape shape{wide_collapse::kMaxLeaf};
  const auto compare = [&](const std::vector<glm::vec3>& positions, const char* name, double most_ratio) {
    const KdTree kept = kept_triangles(positions);
    const binary_bvh::ReferenceChunks references = binary_bvh::make_references(kept.triangles);
    const binary_bvh::Tree with = binary_bvh::build(references, kept.triangles, shape);
    const binary_bvh::Tree without = binary_bvh::build(references, kept.triangles, shape, false);
    EXPECT_EQ(without.size, references.size) << name;
    EXPECT_LE(with.size, references.size + references.size / 4) << name;
    const double ratio = binary_sah(with, shape) / binary_sah(without, shape);
    EXPECT_LE(ratio, most_ratio) << name << ": " << with.size << " references against " << without.size;
    return with.size - without.size;
  };
  EXPECT_GT(compare(crossing_sticks(3'000), "crossing sticks", 0.95), 0u);
  EXPECT_GT(compare(random_soup(5'000, 7), "random soup", 1.0), 0u);
  EXPECT_EQ(compare(coplanar_grid(30, 30), "coplanar grid", 1.0), 0u);
}

TEST(WideCollapse, EightWideLanesGiveTheLeastSah) {
  expect_least_sah<Bvh8fNode, 8>(binary_bvh::LeafShape{wide_collapse::kMaxLeaf, 4u, 0.125f}, {9, 90, 2'000});
}

}  // namespace
}  // namespace cohort::test
