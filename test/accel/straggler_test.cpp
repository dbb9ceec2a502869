// Straggler rays (docs/design.md): no ray may visit a node whose cell it does not touch. Before the
// fix, a direction component of exactly 0 or -0 made kd_inner_step's widening infinite, and such
// rays pushed the far child with the whole interval at every split on that axis: with the old rule
// these tests fail on every scene but one (up to 2.8M of Crytek Sponza's 2.8M nodes for one ray,
// 16,858 of 17,429 on the subdivided Cornell box, 15,466 of 60,000 rays over the bound on the box).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "accel/straggler_check.h"
#include "accel/test_meshes.h"
#include "runtime/scene/scene.h"

namespace cohort::test {
namespace {

void expect_no_stragglers(const std::vector<glm::vec3>& positions, const char* name, std::size_t ray_count) {
  const KdTree tree = build_kdtree(positions);
  const std::vector<TestRay> rays = straggler_rays(tree, ray_count, 4242);
  const std::vector<std::uint32_t> visited = host_visits(tree, rays);
  const StragglerCheck check = check_stragglers(tree, rays, visited);
  fmt::print("[{}] {} nodes, depth {}: {} rays, most nodes visited {}, 99.99th percentile {}, {} over the bound\n",
             name, tree.nodes.size(), tree.stats.depth, check.rays, check.max_visited, check.p9999_visited,
             check.over_bound);
  for (const std::string& w : check.worst) fmt::print("  {}\n", w);
  EXPECT_EQ(check.over_bound, 0u) << name << ": rays visited nodes whose cells they never touch";
}

// Every triangle split into four at its edge midpoints, `levels` times.
std::vector<glm::vec3> subdivide(std::vector<glm::vec3> p, int levels) {
  for (int l = 0; l < levels; ++l) {
    std::vector<glm::vec3> out;
    out.reserve(p.size() * 4);
    for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
      const glm::vec3 a = p[i], b = p[i + 1], c = p[i + 2];
      const glm::vec3 ab = (a + b) * 0.5f, bc = (b + c) * 0.5f, ca = (c + a) * 0.5f;
      for (const glm::vec3& v : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca}) out.push_back(v);
    }
    p = std::move(out);
  }
  return p;
}

std::vector<glm::vec3> shipped(const char* name) {
  return load_scene(std::filesystem::path(COHORT_SOURCE_DIR) / "scenes" / name).positions;
}

TEST(StragglerRays, ShippedCornellBox) { expect_no_stragglers(shipped("cornell-box.gltf"), "cornell box", 60'000); }

TEST(StragglerRays, ShippedCornellBoxSubdividedThreeTimes) {
  expect_no_stragglers(subdivide(shipped("cornell-box.gltf"), 3), "cornell box subdivided", 60'000);
}

TEST(StragglerRays, DegenerateMeshes) {
  expect_no_stragglers(coplanar_grid(100, 100), "coplanar grid", 30'000);
  expect_no_stragglers(triangle_copies(2000), "triangle copies", 10'000);
  expect_no_stragglers(random_soup(20'000, 3), "soup", 30'000);
}

TEST(StragglerRays, SharedModels) {
  const auto bunny = load_shared("bunny/bun_zipper_res2.ply");
  if (!bunny) GTEST_SKIP() << "shared scenes not found";
  expect_no_stragglers(*bunny, "bunny res2", 60'000);
  expect_no_stragglers(subdivide(*bunny, 2), "bunny res2 subdivided twice", 60'000);
  if (const auto sponza = load_shared("crytek-sponza/sponza.obj.gz")) expect_no_stragglers(*sponza, "crytek sponza", 60'000);
}

}  // namespace
}  // namespace cohort::test
