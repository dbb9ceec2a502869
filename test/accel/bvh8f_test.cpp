// The 8-wide BVH with float planes (runtime/accel/bvh8f.h) and its traversal
// (kernels/common/accel/bvh8f_traverse.h compiled as C++, the float8 helpers' lane-by-lane form):
// every node and leaf entry reached once, each lane's box inside its parent's and around its leaf's
// triangles, the same tree for any thread count, and for every ray the KD-tree's, the 4-wide BVH's,
// the compressed 8-wide BVH's and brute force's hit bit for bit, also at shared edges and vertices
// and on degenerate inputs.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>

#include "accel/ray_check.h"
#include "accel/test_meshes.h"
#include "accel/tree_check.h"
#include "runtime/accel/host_traversal.h"
#include "runtime/util/error.h"

namespace cohort::test {
namespace {

// Walks the tree from the root: each node reached once, in depth-first order (each node before its
// children, a lane's subtree after the lanes before it); each lane's box inside its parent's lane;
// leaves within BVH4_LEAF_MAX, their boxes overlapping their triangles (a large triangle's parts
// each in its own leaf) and their copies the kept triangles with the index in v0.w; unused lanes
// BVH4_EMPTY at +infinity; reserved words zero; every leaf entry reached once and every kept
// triangle in 1-64 leaves; the stats the walk's.
std::vector<std::string> structure_errors(const Bvh8f& bvh, const KdTree& tree) {
  std::vector<std::string> errors;
  std::vector<int> seen_node(bvh.nodes.size(), 0), seen_entry(bvh.leaf_vertices.size(), 0),
      seen_triangle(tree.triangles.size(), 0);
  int deepest = 0;
  std::uint32_t next_in_order = 0;
  std::size_t leaves = 0;
  const auto overlaps = [](const Triangle& t, const float lo[3], const float hi[3]) {
    for (int a = 0; a < 3; ++a) {
      const float v[3] = {(&t.v0.x)[a], (&t.v1.x)[a], (&t.v2.x)[a]};
      if (std::max({v[0], v[1], v[2]}) < lo[a] || std::min({v[0], v[1], v[2]}) > hi[a]) return false;
    }
    return true;
  };
  std::function<void(std::uint32_t, int, const float*, const float*)> walk = [&](std::uint32_t index, int depth,
                                                                                  const float* plo, const float* phi) {
    if (index >= bvh.nodes.size() || seen_node[index]++) {
      errors.push_back(fmt::format("node {} reached twice or out of range", index));
      return;
    }
    if (index != next_in_order++) errors.push_back(fmt::format("node {} where a depth-first walk has {}", index, next_in_order - 1));
    deepest = std::max(deepest, depth);
    const Bvh8fNode& n = bvh.nodes[index];
    if (std::any_of(std::begin(n.reserved), std::end(n.reserved), [](std::uint32_t r) { return r != 0; }))
      errors.push_back(fmt::format("node {}: reserved words not zero", index));
    int used = 0;
    for (int lane = 0; lane < 8; ++lane) {
      const std::uint32_t ref = n.child[lane];
      const float lo[3] = {n.planes[0][lane], n.planes[2][lane], n.planes[4][lane]};
      const float hi[3] = {n.planes[1][lane], n.planes[3][lane], n.planes[5][lane]};
      if (ref == BVH4_EMPTY) {
        for (int a = 0; a < 3; ++a)
          if (lo[a] != INFINITY || hi[a] != INFINITY)
            errors.push_back(fmt::format("node {} lane {}: empty lane with a box", index, lane));
        continue;
      }
      ++used;
      for (int a = 0; a < 3; ++a)
        if (!(lo[a] <= hi[a]) || (plo && (lo[a] < plo[a] || hi[a] > phi[a])))
          errors.push_back(fmt::format("node {} lane {}: box outside its parent's or inverted", index, lane));
      if (!bvh4_is_leaf(ref)) {
        walk(ref, depth + 1, lo, hi);
        continue;
      }
      ++leaves;
      const std::uint32_t first = bvh4_leaf_first(ref), count = bvh4_leaf_count(ref);
      if (count > BVH4_LEAF_MAX || first + count > bvh.leaf_vertices.size()) {
        errors.push_back(fmt::format("node {} lane {}: leaf [{}, +{}) out of range", index, lane, first, count));
        continue;
      }
      for (std::uint32_t i = first; i < first + count; ++i) {
        ++seen_entry[i];
        const std::uint32_t tri = co_as_uint(bvh.leaf_vertices[i].v0.w);
        if (tri >= tree.triangles.size()) { errors.push_back("leaf entry out of range"); continue; }
        ++seen_triangle[tri];
        if (!overlaps(tree.triangles[tri], lo, hi)) errors.push_back(fmt::format("triangle {} outside its leaf box", tri));
        Triangle expected = tree.triangles[tri];
        expected.v0.w = co_as_float(tri);
        if (std::memcmp(&bvh.leaf_vertices[i], &expected, sizeof(Triangle)) != 0)
          errors.push_back(fmt::format("leaf entry {}: its copy is not triangle {}", i, tri));
      }
    }
    if (used == 0) errors.push_back(fmt::format("node {} has no children", index));
  };
  walk(0, 1, nullptr, nullptr);
  for (std::size_t i = 0; i < seen_node.size(); ++i)
    if (!seen_node[i]) errors.push_back(fmt::format("node {} unreachable", i));
  for (std::size_t i = 0; i < seen_entry.size(); ++i)
    if (seen_entry[i] != 1) errors.push_back(fmt::format("leaf entry {} reached {} times", i, seen_entry[i]));
  if (bvh.leaf_vertices.size() != bvh.stats.references) errors.push_back("leaf entries are not the references");
  for (std::size_t i = 0; i < seen_triangle.size(); ++i)
    if (seen_triangle[i] < 1 || seen_triangle[i] > 64) errors.push_back(fmt::format("triangle {} in {} leaves", i, seen_triangle[i]));
  if (leaves != bvh.stats.leaf_count) errors.push_back(fmt::format("{} leaves but stats say {}", leaves, bvh.stats.leaf_count));
  if (deepest != bvh.stats.depth) errors.push_back(fmt::format("depth {} but stats say {}", deepest, bvh.stats.depth));
  if (deepest > BVH4_MAX_DEPTH) errors.push_back(fmt::format("depth {} over BVH4_MAX_DEPTH", deepest));
  if (errors.size() > 10) errors.resize(10);
  return errors;
}

// Feature rays (at shared vertices and edge midpoints), rays in split planes and random ones: the
// closest hit through the 8-wide BVH with float planes against the deep KD-tree's, the 4-wide BVH's
// and the compressed 8-wide BVH's, bit for bit, and against brute force on every 8th ray; any hit
// before half and 1.5 times the closest distance.
void expect_same_hits_as_every_tree(const std::vector<glm::vec3>& positions, const char* name) {
  const KdTree kd = build_kdtree(positions);
  const KdTree kept = kept_triangles(positions);
  ASSERT_EQ(kd.triangles.size(), kept.triangles.size());
  const Bvh8f bvh = build_bvh8f(kept.triangles);
  const Bvh4 bvh4 = build_bvh4(kept.triangles);
  const Bvh8 bvh8 = build_bvh8(kept.triangles);
  for (const std::string& e : structure_errors(bvh, kept)) ADD_FAILURE() << name << ": " << e;
  const KdTreeView kv = view_of(kd);
  const Bvh8fView bv = host_view(bvh);
  const Bvh4View b4 = host_view(bvh4);
  const Bvh8View b8 = host_view(bvh8);
  std::vector<TestRay> rays = make_feature_rays(kd, 20'000, 41);
  const std::vector<TestRay> random = make_rays(kd.bounds, 10'000, 42);
  rays.insert(rays.end(), random.begin(), random.end());
  const std::vector<TestRay> in_planes = make_split_plane_rays(kd, 10'000, 43);
  rays.insert(rays.end(), in_planes.begin(), in_planes.end());
  std::size_t hits = 0, differ = 0, differ4 = 0, differ8 = 0, brute_differ = 0, occlusion_differ = 0;
  std::uint64_t steps8f = 0, steps4 = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const TestRay& ray = rays[i];
    const co_vec3 org = v3(ray.org.x, ray.org.y, ray.org.z), dir = v3(ray.dir.x, ray.dir.y, ray.dir.z);
    std::uint32_t s8f = 0, s4 = 0;
    const HitOut k = kd_trace(&kv, org, dir, 0.f, kInf, 0);
    const HitOut b = bvh8f_trace_steps(&bv, org, dir, 0.f, kInf, 0, &s8f);
    const HitOut f = bvh4_trace_steps(&b4, org, dir, 0.f, kInf, 0, &s4);
    const HitOut e8 = bvh8_trace_steps(&b8, org, dir, 0.f, kInf, 0, nullptr);
    steps8f += s8f;
    steps4 += s4;
    hits += k.triangle != HIT_NONE;
    differ += std::memcmp(&k, &b, sizeof(HitOut)) != 0;
    differ4 += std::memcmp(&f, &b, sizeof(HitOut)) != 0;
    differ8 += std::memcmp(&e8, &b, sizeof(HitOut)) != 0;
    if (i % 8 == 0) {
      const HitOut e = brute_force(kept, ray, 0.f, kInf);
      brute_differ += std::memcmp(&e, &b, sizeof(HitOut)) != 0;
    }
    for (const float limit : {0.5f, 1.5f}) {
      const float tmax = k.triangle != HIT_NONE ? limit * k.t : kInf;
      occlusion_differ += (kd_trace(&kv, org, dir, 0.f, tmax, 1).triangle != HIT_NONE) !=
                          (bvh8f_trace_steps(&bv, org, dir, 0.f, tmax, 1, nullptr).triangle != HIT_NONE);
    }
  }
  fmt::print("[{}] {} rays, {} hits; 8-wide BVH (float planes) {} nodes depth {}: {} closest hits differ from the "
             "KD-tree's, {} from the 4-wide BVH's, {} from the compressed 8-wide BVH's, {} from brute force's, {} "
             "any-hit answers; {:.1f} nodes + leaves per ray (4-wide: {:.1f})\n",
             name, rays.size(), hits, bvh.stats.node_count, bvh.stats.depth, differ, differ4, differ8, brute_differ,
             occlusion_differ, double(steps8f) / rays.size(), double(steps4) / rays.size());
  EXPECT_GT(hits, rays.size() / 4);
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(differ4, 0u);
  EXPECT_EQ(differ8, 0u);
  EXPECT_EQ(brute_differ, 0u);
  EXPECT_EQ(occlusion_differ, 0u);
}

TEST(Bvh8f, GivesEveryTreesHitsBitForBit) {
  expect_same_hits_as_every_tree(coplanar_grid(100, 100), "20k coplanar");
  expect_same_hits_as_every_tree(random_soup(4000, 7), "soup");
  expect_same_hits_as_every_tree(load_shipped("voxel-terrain.gltf"), "voxel terrain");
  for (const char* model : {"bunny/bun_zipper_res2.ply", "cornell-box-mcguire/CornellBox-Original.obj"})
    if (const auto positions = load_shared(model)) expect_same_hits_as_every_tree(*positions, model);
}

// The same binary tree collapsed at width 8 holds the same leaves as the 4-wide BVH's (the same
// leaf entries in the same order) in fewer nodes.
TEST(Bvh8f, HasTheFourWideLeavesInFewerNodes) {
  const KdTree kept = kept_triangles(random_soup(20'000, 5));
  const Bvh8f wide = build_bvh8f(kept.triangles);
  const Bvh4 narrow = build_bvh4(kept.triangles);
  ASSERT_EQ(wide.leaf_vertices.size(), narrow.leaf_vertices.size());
  EXPECT_EQ(0, std::memcmp(wide.leaf_vertices.data(), narrow.leaf_vertices.data(),
                           wide.leaf_vertices.size() * sizeof(Triangle)));
  EXPECT_EQ(wide.stats.leaf_count, narrow.stats.leaf_count);
  EXPECT_LT(wide.stats.node_count, narrow.stats.node_count * 3 / 4);  // 0.64x on this soup
  EXPECT_LT(wide.stats.depth, narrow.stats.depth);
}

TEST(Bvh8f, SameTreeForAnyThreadCount) {
  const KdTree kept = kept_triangles(random_soup(20'000, 3));
  const Bvh8f many = build_bvh8f(kept.triangles);
  tbb::task_arena one(1);
  const Bvh8f single = one.execute([&] { return build_bvh8f(kept.triangles); });
  ASSERT_EQ(many.nodes.size(), single.nodes.size());
  EXPECT_EQ(0, std::memcmp(many.nodes.data(), single.nodes.data(), many.nodes.size() * sizeof(Bvh8fNode)));
  ASSERT_EQ(many.leaf_vertices.size(), single.leaf_vertices.size());
  EXPECT_EQ(0, std::memcmp(many.leaf_vertices.data(), single.leaf_vertices.data(),
                           many.leaf_vertices.size() * sizeof(Triangle)));
  EXPECT_TRUE(structure_errors(many, kept).empty());
  EXPECT_EQ(many.stats.sah_cost, single.stats.sah_cost);
  EXPECT_EQ(many.stats.leaf_count, single.stats.leaf_count);
  EXPECT_EQ(many.stats.depth, single.stats.depth);
}

// Where a binned build has nothing to bin (one triangle; 1000 copies of one, every centroid in one
// point; centroids halving their distance each time): sound trees, and through the copies the first
// copy's hit (the least index at equal t), found through a node whose eight lanes all enter at the
// same distance (the stack's insertion at equal keys).
TEST(Bvh8f, DegenerateInputsStaySoundAndFindTheLowestIndex) {
  const std::vector<glm::vec3> one{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  std::vector<glm::vec3> copies, halving;
  for (int i = 0; i < 1000; ++i) copies.insert(copies.end(), one.begin(), one.end());
  for (int i = 0; i < 300; ++i) {
    const float x = std::ldexp(1.0f, -i / 3);
    const float s = std::ldexp(1.0f, -i / 3 - 8);
    halving.insert(halving.end(), {{x, 0, float(i % 3)}, {x + s, 0, float(i % 3)}, {x, s, float(i % 3)}});
  }
  for (const std::vector<glm::vec3>* positions : std::array<const std::vector<glm::vec3>*, 3>{&one, &copies, &halving}) {
    const KdTree kept = kept_triangles(*positions);
    const Bvh8f bvh = build_bvh8f(kept.triangles);
    for (const std::string& e : structure_errors(bvh, kept)) ADD_FAILURE() << e;
  }
  const KdTree kept = kept_triangles(copies);
  const Bvh8f bvh = build_bvh8f(kept.triangles);
  const Bvh8fView view = host_view(bvh);
  const HitOut hit = bvh8f_trace_steps(&view, v3(0.2f, 0.2f, 0.f), v3(0.f, 0.f, 1.f), 0.f, kInf, 0, nullptr);
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_EQ(hit.t, 1.0f);
}

// As Bvh4.ARayWithANanDirectionMisses: a NaN direction component misses instead of walking out of
// the arrays (the trees share bvh4_inverse).
TEST(Bvh8f, ARayWithANanDirectionMisses) {
  const KdTree kept = kept_triangles(random_soup(4000, 7));
  const Bvh8f bvh = build_bvh8f(kept.triangles);
  const Bvh8fView view = host_view(bvh);
  EXPECT_NE(bvh8f_trace_steps(&view, v3(0.f, 0.f, 0.f), v3(0.f, 0.f, 1.f), 0.f, kInf, 0, nullptr).triangle, HIT_NONE);
  const float nan = std::nanf("");
  for (const co_vec3 dir : {v3(nan, 0.f, 1.f), v3(0.f, nan, 0.f), v3(nan, nan, nan), v3(0.3f, -0.2f, nan)})
    for (const int any_hit : {0, 1})
      EXPECT_EQ(bvh8f_trace_steps(&view, v3(0.f, 0.f, 0.f), dir, 0.f, kInf, any_hit, nullptr).triangle, HIT_NONE);
}

TEST(Bvh8f, RejectsAnEmptyInput) {
  EXPECT_THROW(build_bvh8f({}), InputError);
}

}  // namespace
}  // namespace cohort::test
