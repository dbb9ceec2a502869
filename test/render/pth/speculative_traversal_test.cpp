// The speculative traversal's per-ray state machine (kernels/common/pth/kdtree_speculative.h, compiled
// as C++) run in emulated SIMD groups with the group vote done on the host: every ray must find
// kd_trace's hit bit for bit, whatever the group size and whatever its neighbours do.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>

#include "accel/ray_check.h"
#include "accel/test_meshes.h"
#include "kernels/common/pth/kdtree_speculative.h"

namespace cohort::test {
namespace {

struct GroupRun {
  std::size_t mismatches = 0;
  std::uint64_t speculative_steps = 0;  // nodes visited with speculation
  std::uint64_t plain_steps = 0;        // nodes kd_trace visits
  std::uint64_t leaf_phases = 0;
};

GroupRun run_groups(const KdTree& tree, const std::vector<TestRay>& rays, std::size_t group) {
  const KdTreeView view = view_of(tree);
  GroupRun run;
  std::vector<KdSpeculativeRay> state(group);
  std::vector<std::array<KdStackEntry, KD_MAX_DEPTH>> stacks(group);
  for (std::size_t first = 0; first < rays.size(); first += group) {
    for (std::size_t l = 0; l < group; ++l) {
      const std::size_t i = first + l;
      const TestRay r = i < rays.size() ? rays[i] : rays[0];
      const co_vec3 org = v3(r.org.x, r.org.y, r.org.z), dir = v3(r.dir.x, r.dir.y, r.dir.z);
      float t0 = 0, t1 = 0;
      const int active = i < rays.size() && kd_begin(&view, org, kd_inverse(dir), 0.0f, INFINITY, &t0, &t1);
      kd_spec_start(&state[l], active, org, dir, 0.0f, INFINITY, 0u, t0, t1, 0);
    }
    // the kernel's group loop, with the vote as a plain OR over the lanes
    for (;;) {
      std::uint32_t vote = 0;
      for (const auto& s : state) vote |= kd_spec_vote_bits(&s);
      if (!(vote & KD_VOTE_ACTIVE)) break;
      if (vote & KD_VOTE_SEARCHING) {
        for (std::size_t l = 0; l < group; ++l) kd_spec_walk_step(&view, &state[l], stacks[l].data());
      } else {
        ++run.leaf_phases;
        for (auto& s : state) kd_spec_leaf_phase(&view, &s);
      }
    }
    for (std::size_t l = 0; l < group && first + l < rays.size(); ++l) {
      const TestRay& r = rays[first + l];
      std::uint32_t steps = 0;
      const HitOut expected =
          kd_trace_steps(&view, v3(r.org.x, r.org.y, r.org.z), v3(r.dir.x, r.dir.y, r.dir.z), 0.0f, INFINITY, 0, &steps);
      run.mismatches += std::memcmp(&expected, &state[l].hit, sizeof(HitOut)) != 0;
      run.plain_steps += steps;
      run.speculative_steps += state[l].visited;
    }
  }
  return run;
}

void expect_same_hits(const std::vector<glm::vec3>& positions, const char* name) {
  const KdTree tree = build_kdtree(positions);
  std::vector<TestRay> rays = make_rays(tree.bounds, 20'000, 99);
  const std::vector<TestRay> feature = make_feature_rays(tree, 5'000, 7);
  rays.insert(rays.end(), feature.begin(), feature.end());
  const std::vector<TestRay> in_planes = make_split_plane_rays(tree, 5'000, 8);  // unordered stacks too
  rays.insert(rays.end(), in_planes.begin(), in_planes.end());
  for (std::size_t group : {1u, 7u, 32u}) {
    const GroupRun run = run_groups(tree, rays, group);
    fmt::print("[{}] group {}: {} rays, {} hit differences, {:.2f} nodes per ray speculative vs {:.2f} plain, "
               "{} leaf phases\n",
               name, group, rays.size(), run.mismatches, double(run.speculative_steps) / rays.size(),
               double(run.plain_steps) / rays.size(), run.leaf_phases);
    EXPECT_EQ(run.mismatches, 0u) << name << ", group " << group;
    // speculation only adds inner steps, never skips a node kd_trace visits on the way to its hit
    EXPECT_GE(run.speculative_steps, run.plain_steps) << name << ", group " << group;
    if (group == 1) {
      EXPECT_EQ(run.speculative_steps, run.plain_steps) << "a lone ray has nobody to wait for";
    }
  }
}

TEST(SpeculativeTraversal, SoupSameHitsAsKdTrace) { expect_same_hits(random_soup(3000, 5), "soup"); }

TEST(SpeculativeTraversal, VoxelTerrainSameHitsAsKdTrace) {
  expect_same_hits(load_shipped("voxel-terrain.gltf"), "voxel terrain");
}

TEST(SpeculativeTraversal, BunnySameHitsAsKdTrace) {
  const auto positions = load_shared("bunny/bun_zipper_res3.ply");
  if (!positions) GTEST_SKIP() << "shared scenes not found";
  expect_same_hits(*positions, "bunny res3");
}

}  // namespace
}  // namespace cohort::test
