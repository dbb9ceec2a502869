// The 4-wide BVH (runtime/accel/bvh4.h) and its traversal (kernels/common/accel/bvh4_traverse.h compiled
// as C++): every triangle once, inside its boxes, the same tree for any thread count, and for every
// ray the KD-tree's hit bit for bit, also at shared edges and vertices and on degenerate inputs.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <climits>
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

// Walks the tree: each node reached once and where the layout puts it, each lane's box inside its parent's, leaves within
// BVH4_LEAF_MAX and their boxes overlapping their triangles (a large triangle is split into parts,
// each in its own leaf with the box of its part), unused lanes empty; every kept triangle in some
// leaf, and in no more than the 64 parts a triangle is split into at most.
std::vector<std::string> structure_errors(const Bvh4& bvh, const KdTree& tree) {
  std::vector<std::string> errors;
  std::vector<int> seen_node(bvh.nodes.size(), 0), seen_triangle(tree.triangles.size(), 0);
  int deepest = 0;
  // the top levels breadth first (each depth a range of top_level_starts), the rest depth first
  const auto& starts = bvh.top_level_starts;
  std::uint32_t next_in_order = starts.empty() ? 0 : starts.back();
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
    // below the top, depth-first order: each node before its children, a lane's subtree after the
    // lanes before it
    if (std::size_t(depth) < starts.size()) {
      if (index < starts[depth - 1] || index >= starts[depth])
        errors.push_back(fmt::format("node {} at depth {} outside the top's range for it", index, depth));
    } else if (index != next_in_order++) {
      errors.push_back(fmt::format("node {} where a depth-first walk has {}", index, next_in_order - 1));
    }
    deepest = std::max(deepest, depth);
    const Bvh4Node& n = bvh.nodes[index];
    if (n.reserved.x || n.reserved.y || n.reserved.z || n.reserved.w) errors.push_back("reserved words not zero");
    for (int lane = 0; lane < 4; ++lane) {
      const std::uint32_t ref = (&n.child.x)[lane];
      const float lo[3] = {(&n.lo_x.x)[lane], (&n.lo_y.x)[lane], (&n.lo_z.x)[lane]};
      const float hi[3] = {(&n.hi_x.x)[lane], (&n.hi_y.x)[lane], (&n.hi_z.x)[lane]};
      if (ref == BVH4_EMPTY) {
        if (lo[0] != INFINITY || hi[0] != INFINITY) errors.push_back(fmt::format("node {} lane {}: empty lane with a box", index, lane));
        continue;
      }
      for (int a = 0; a < 3; ++a)
        if (plo && (lo[a] < plo[a] || hi[a] > phi[a]))
          errors.push_back(fmt::format("node {} lane {}: box outside its parent's", index, lane));
      if (bvh4_is_leaf(ref)) {
        ++leaves;
        const std::uint32_t first = bvh4_leaf_first(ref), count = bvh4_leaf_count(ref);
        if (count > BVH4_LEAF_MAX || first + count > bvh.leaf_vertices.size()) {
          errors.push_back(fmt::format("node {} lane {}: leaf [{}, +{}) out of range", index, lane, first, count));
          continue;
        }
        for (std::uint32_t i = first; i < first + count; ++i) {
          const std::uint32_t tri = co_as_uint(bvh.leaf_vertices[i].v0.w);
          if (tri >= tree.triangles.size()) { errors.push_back("leaf entry out of range"); continue; }
          ++seen_triangle[tri];
          if (!overlaps(tree.triangles[tri], lo, hi)) errors.push_back(fmt::format("triangle {} outside its leaf box", tri));
          // the device reads the copy: the same vertices, the index in v0.w
          Triangle expected = tree.triangles[tri];
          expected.v0.w = co_as_float(tri);
          if (std::memcmp(&bvh.leaf_vertices[i], &expected, sizeof(Triangle)) != 0)
            errors.push_back(fmt::format("leaf entry {}: its copy is not triangle {}", i, tri));
        }
      } else {
        walk(ref, depth + 1, lo, hi);
      }
    }
  };
  walk(0, 1, nullptr, nullptr);
  for (std::size_t i = 0; i < seen_node.size(); ++i)
    if (!seen_node[i]) errors.push_back(fmt::format("node {} unreachable", i));
  for (std::size_t i = 0; i < seen_triangle.size(); ++i)
    if (seen_triangle[i] < 1 || seen_triangle[i] > 64) errors.push_back(fmt::format("triangle {} in {} leaves", i, seen_triangle[i]));
  if (leaves != bvh.stats.leaf_count)
    errors.push_back(fmt::format("{} leaves but stats say {}", leaves, bvh.stats.leaf_count));
  if (deepest != bvh.stats.depth) errors.push_back(fmt::format("depth {} but stats say {}", deepest, bvh.stats.depth));
  if (deepest > BVH4_MAX_DEPTH) errors.push_back(fmt::format("depth {} over BVH4_MAX_DEPTH", deepest));
  if (errors.size() > 10) errors.resize(10);
  return errors;
}

// Feature rays (at shared vertices and edge midpoints), rays from split planes and random ones: closest hit through the BVH
// against the deep KD-tree's, bit for bit, and against brute force on every 16th ray; any hit before
// half the closest distance and before 1.5 times it.
void expect_kd_hits(const std::vector<glm::vec3>& positions, const char* name) {
  const KdTree kd = build_kdtree(positions);
  const KdTree kept = kept_triangles(positions);
  ASSERT_EQ(kd.triangles.size(), kept.triangles.size());
  ASSERT_EQ(0, std::memcmp(kd.triangles.data(), kept.triangles.data(), kd.triangles.size() * sizeof(Triangle)));
  const Bvh4 bvh = build_bvh4(kept.triangles);
  const std::vector<std::string> errors = structure_errors(bvh, kept);
  for (const std::string& e : errors) ADD_FAILURE() << name << ": " << e;
  const KdTreeView kv = view_of(kd);
  const Bvh4View bv = host_view(bvh);
  std::vector<TestRay> rays = make_feature_rays(kd, 20'000, 41);
  const std::vector<TestRay> random = make_rays(kd.bounds, 10'000, 42);
  rays.insert(rays.end(), random.begin(), random.end());
  const std::vector<TestRay> in_planes = make_split_plane_rays(kd, 10'000, 43);
  rays.insert(rays.end(), in_planes.begin(), in_planes.end());
  std::size_t hits = 0, differ = 0, brute_differ = 0, occlusion_differ = 0;
  std::uint64_t kd_steps = 0, bvh_steps = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const TestRay& ray = rays[i];
    const co_vec3 org = v3(ray.org.x, ray.org.y, ray.org.z), dir = v3(ray.dir.x, ray.dir.y, ray.dir.z);
    std::uint32_t ks = 0, bs = 0;
    const HitOut k = kd_trace_steps(&kv, org, dir, 0.f, kInf, 0, &ks);
    const HitOut b = bvh4_trace_steps(&bv, org, dir, 0.f, kInf, 0, &bs);
    kd_steps += ks;
    bvh_steps += bs;
    hits += k.triangle != HIT_NONE;
    differ += std::memcmp(&k, &b, sizeof(HitOut)) != 0;
    if (i % 16 == 0) {
      const HitOut e = brute_force(kept, ray, 0.f, kInf);
      brute_differ += std::memcmp(&e, &b, sizeof(HitOut)) != 0;
    }
    for (const float limit : {0.5f, 1.5f}) {
      const float tmax = k.triangle != HIT_NONE ? limit * k.t : kInf;
      occlusion_differ += (kd_trace(&kv, org, dir, 0.f, tmax, 1).triangle != HIT_NONE) !=
                          (bvh4_trace_steps(&bv, org, dir, 0.f, tmax, 1, nullptr).triangle != HIT_NONE);
    }
  }
  fmt::print("[{}] {} rays, {} hits; BVH {} nodes depth {}: {} closest hits, {} of brute force's and {} any-hit "
             "answers differ; {:.1f} KD visits against {:.1f} BVH visits per ray\n",
             name, rays.size(), hits, bvh.stats.node_count, bvh.stats.depth, differ, brute_differ, occlusion_differ,
             double(kd_steps) / rays.size(), double(bvh_steps) / rays.size());
  EXPECT_GT(hits, rays.size() / 4);
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(brute_differ, 0u);
  EXPECT_EQ(occlusion_differ, 0u);
}

TEST(Bvh4, GivesTheKdTreesHitsBitForBit) {
  expect_kd_hits(coplanar_grid(100, 100), "20k coplanar");
  expect_kd_hits(random_soup(4000, 7), "soup");
  expect_kd_hits(load_shipped("voxel-terrain.gltf"), "voxel terrain");
  for (const char* model : {"bunny/bun_zipper_res2.ply", "cornell-box-mcguire/CornellBox-Original.obj"})
    if (const auto positions = load_shared(model)) expect_kd_hits(*positions, model);
}

TEST(Bvh4, SameTreeForAnyThreadCount) {
  const KdTree kept = kept_triangles(random_soup(20'000, 3));
  const Bvh4 many = build_bvh4(kept.triangles);
  tbb::task_arena one(1);
  const Bvh4 single = one.execute([&] { return build_bvh4(kept.triangles); });
  ASSERT_EQ(many.nodes.size(), single.nodes.size());
  EXPECT_EQ(0, std::memcmp(many.nodes.data(), single.nodes.data(), many.nodes.size() * sizeof(Bvh4Node)));
  ASSERT_EQ(many.leaf_vertices.size(), single.leaf_vertices.size());
  EXPECT_EQ(0, std::memcmp(many.leaf_vertices.data(), single.leaf_vertices.data(),
                           many.leaf_vertices.size() * sizeof(Triangle)));
  EXPECT_TRUE(structure_errors(many, kept).empty());
  // the statistics are summed per subtree and joined in lane order: the same figures too
  EXPECT_EQ(many.stats.sah_cost, single.stats.sah_cost);
  EXPECT_EQ(many.stats.leaf_count, single.stats.leaf_count);
  EXPECT_EQ(many.stats.depth, single.stats.depth);
}

// Where a binned build has nothing to bin: one triangle; many copies of one triangle (every
// centroid in one point); triangles whose centroids halve their distance each time (each SAH split
// peels off one, which the object-median fallback must stop before the stack depth).
TEST(Bvh4, DegenerateInputsStayShallowAndFindTheLowestIndex) {
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
    const Bvh4 bvh = build_bvh4(kept.triangles);
    const std::vector<std::string> errors = structure_errors(bvh, kept);
    for (const std::string& e : errors) ADD_FAILURE() << e;
    EXPECT_LE(bvh.stats.depth, BVH4_MAX_DEPTH);
  }
  // through the 1000 copies, the hit is the first copy's (the least index at equal t)
  const KdTree kept = kept_triangles(copies);
  const Bvh4 bvh = build_bvh4(kept.triangles);
  const Bvh4View view = host_view(bvh);
  const HitOut hit = bvh4_trace_steps(&view, v3(0.2f, 0.2f, 0.f), v3(0.f, 0.f, 1.f), 0.f, kInf, 0, nullptr);
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_EQ(hit.t, 1.0f);
}

// A ray whose direction has a NaN component (nothing the renderer should make, but a degenerate
// input can) misses on every tree instead of walking out of the arrays.
TEST(Bvh4, ARayWithANanDirectionMisses) {
  const KdTree kept = kept_triangles(random_soup(4000, 7));  // a soup around the origin
  const Bvh4 bvh = build_bvh4(kept.triangles);
  const Bvh4View view = host_view(bvh);
  EXPECT_NE(bvh4_trace_steps(&view, v3(0.f, 0.f, 0.f), v3(0.f, 0.f, 1.f), 0.f, kInf, 0, nullptr).triangle, HIT_NONE);
  const float nan = std::nanf("");
  for (const co_vec3 dir : {v3(nan, 0.f, 1.f), v3(0.f, nan, 0.f), v3(nan, nan, nan), v3(0.3f, -0.2f, nan)}) {
    for (const int any_hit : {0, 1}) {
      const HitOut hit = bvh4_trace_steps(&view, v3(0.f, 0.f, 0.f), dir, 0.f, kInf, any_hit, nullptr);
      EXPECT_EQ(hit.triangle, HIT_NONE);
    }
  }
}

TEST(Bvh4, RejectsAnEmptyInput) {
  EXPECT_THROW(build_bvh4({}), InputError);
}

}  // namespace
}  // namespace cohort::test
