// The compressed 8-wide BVH (runtime/accel/bvh8.h) and its traversal (kernels/common/accel/bvh8_traverse.h
// compiled as C++): every reference reached once, decoded child boxes around their subtrees and exact
// with or without fma, the same tree for any thread count, and for every ray the KD-tree's and brute
// force's hit bit for bit, also at shared edges and vertices and on degenerate inputs.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <bit>
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

std::uint32_t meta_of(const Bvh8Node& n, int slot) { return ((slot < 4 ? n.index.z : n.index.w) >> (8 * (slot % 4))) & 255u; }

// Walks the tree from the root: each node reached once and where its parent's child base and imask
// put it; every used slot's decoded box inside its parent's, exact in float whether or not the
// multiply-add is fused; an inner child's box around every box of its children, a leaf's around
// (overlapping) its triangles' parts; leaves of 1-3 triangles within the node's 24 offsets; unused
// slots with meta 0; every leaf entry reached exactly once (each reference once) and each kept
// triangle in 1-64 leaves.
std::vector<std::string> structure_errors(const Bvh8& bvh, const KdTree& tree) {
  std::vector<std::string> errors;
  std::vector<int> seen_node(bvh.nodes.size(), 0), seen_entry(bvh.leaf_vertices.size(), 0),
      seen_triangle(tree.triangles.size(), 0);
  int deepest = 0;
  std::size_t leaves = 0;
  const auto overlaps = [](const Triangle& t, const std::array<float, 6>& box) {
    for (int a = 0; a < 3; ++a) {
      const float v[3] = {(&t.v0.x)[a], (&t.v1.x)[a], (&t.v2.x)[a]};
      if (std::max({v[0], v[1], v[2]}) < box[a] || std::min({v[0], v[1], v[2]}) > box[a + 3]) return false;
    }
    return true;
  };
  const auto inside = [](const std::array<float, 6>& in, const std::array<float, 6>& out) {
    for (int a = 0; a < 3; ++a)
      if (in[a] < out[a] || in[a + 3] > out[a + 3]) return false;
    return true;
  };
  std::function<void(std::uint32_t, int, const std::array<float, 6>*)> walk = [&](std::uint32_t index, int depth,
                                                                                  const std::array<float, 6>* parent) {
    if (index >= bvh.nodes.size() || seen_node[index]++) {
      errors.push_back(fmt::format("node {} reached twice or out of range", index));
      return;
    }
    deepest = std::max(deepest, depth);
    const Bvh8Node& n = bvh.nodes[index];
    const std::uint32_t imask = n.header.w >> 24;
    std::uint32_t used_offsets = 0;
    int children = 0;
    for (int s = 0; s < 8; ++s) {
      const std::uint32_t m = meta_of(n, s);
      if (m == 0) {
        if (imask & (1u << s)) errors.push_back(fmt::format("node {} slot {}: inner without meta", index, s));
        continue;
      }
      ++children;
      const std::array<float, 6> box = bvh8_child_box(n, s);
      for (int p = 0; p < 6; ++p) {
        const int a = p % 3;
        const float origin = co_as_float((&n.header.x)[a]);
        const float scale = co_as_float(((n.header.w >> (8 * a)) & 255u) << 23);
        const float q = (box[p] - origin) / scale;
        if (std::fma(q, scale, origin) != box[p] || double(origin) + double(q) * scale != double(box[p]))
          errors.push_back(fmt::format("node {} slot {}: plane {} not exact", index, s, p));
      }
      if (parent && !inside(box, *parent))
        errors.push_back(fmt::format("node {} slot {}: box outside its parent's", index, s));
      if (imask & (1u << s)) {
        if (m != 0x20u + 24u + s) errors.push_back(fmt::format("node {} slot {}: inner meta {:#x}", index, s, m));
        const std::uint32_t child = n.index.x + std::popcount(imask & ((1u << s) - 1u));
        walk(child, depth + 1, &box);
        continue;
      }
      ++leaves;
      const std::uint32_t count = std::popcount(m >> 5), offset = m & 31u;
      if ((m >> 5) != (1u << count) - 1u || count == 0 || count > BVH8_LEAF_MAX || offset + count > 24) {
        errors.push_back(fmt::format("node {} slot {}: leaf meta {:#x}", index, s, m));
        continue;
      }
      const std::uint32_t bits = ((1u << count) - 1u) << offset;
      if (used_offsets & bits) errors.push_back(fmt::format("node {} slot {}: triangle offsets shared", index, s));
      used_offsets |= bits;
      for (std::uint32_t i = n.index.y + offset; i < n.index.y + offset + count; ++i) {
        if (i >= bvh.leaf_vertices.size()) { errors.push_back("leaf entry out of range"); continue; }
        ++seen_entry[i];
        const std::uint32_t tri = co_as_uint(bvh.leaf_vertices[i].v0.w);
        if (tri >= tree.triangles.size()) { errors.push_back("leaf triangle out of range"); continue; }
        ++seen_triangle[tri];
        if (!overlaps(tree.triangles[tri], box)) errors.push_back(fmt::format("triangle {} outside its leaf box", tri));
        Triangle expected = tree.triangles[tri];
        expected.v0.w = co_as_float(tri);
        if (std::memcmp(&bvh.leaf_vertices[i], &expected, sizeof(Triangle)) != 0)
          errors.push_back(fmt::format("leaf entry {}: its copy is not triangle {}", i, tri));
      }
    }
    if (children == 0) errors.push_back(fmt::format("node {} has no children", index));
  };
  walk(0, 1, nullptr);
  for (std::size_t i = 0; i < seen_node.size(); ++i)
    if (!seen_node[i]) errors.push_back(fmt::format("node {} unreachable", i));
  for (std::size_t i = 0; i < seen_entry.size(); ++i)
    if (seen_entry[i] != 1) errors.push_back(fmt::format("leaf entry {} reached {} times", i, seen_entry[i]));
  if (bvh.leaf_vertices.size() != bvh.stats.references) errors.push_back("leaf entries are not the references");
  for (std::size_t i = 0; i < seen_triangle.size(); ++i)
    if (seen_triangle[i] < 1 || seen_triangle[i] > 64) errors.push_back(fmt::format("triangle {} in {} leaves", i, seen_triangle[i]));
  if (leaves != bvh.stats.leaf_count) errors.push_back(fmt::format("{} leaves but stats say {}", leaves, bvh.stats.leaf_count));
  if (deepest != bvh.stats.depth) errors.push_back(fmt::format("depth {} but stats say {}", deepest, bvh.stats.depth));
  if (deepest > BVH8_STACK) errors.push_back(fmt::format("depth {} over the stack", deepest));
  if (errors.size() > 10) errors.resize(10);
  return errors;
}

// Feature rays (at shared vertices and edge midpoints), rays in split planes and random ones: the
// closest hit through the 8-wide BVH against the deep KD-tree's and the 4-wide BVH's, bit for bit,
// and against brute force on every 8th ray; any hit before half and 1.5 times the closest distance.
void expect_same_hits(const std::vector<glm::vec3>& positions, const char* name) {
  const KdTree kd = build_kdtree(positions);
  const KdTree kept = kept_triangles(positions);
  ASSERT_EQ(kd.triangles.size(), kept.triangles.size());
  const Bvh8 bvh = build_bvh8(kept.triangles);
  const Bvh4 bvh4 = build_bvh4(kept.triangles);
  for (const std::string& e : structure_errors(bvh, kept)) ADD_FAILURE() << name << ": " << e;
  const KdTreeView kv = view_of(kd);
  const Bvh8View bv = host_view(bvh);
  const Bvh4View b4 = host_view(bvh4);
  std::vector<TestRay> rays = make_feature_rays(kd, 20'000, 41);
  const std::vector<TestRay> random = make_rays(kd.bounds, 10'000, 42);
  rays.insert(rays.end(), random.begin(), random.end());
  const std::vector<TestRay> in_planes = make_split_plane_rays(kd, 10'000, 43);
  rays.insert(rays.end(), in_planes.begin(), in_planes.end());
  std::size_t hits = 0, differ = 0, differ4 = 0, brute_differ = 0, occlusion_differ = 0;
  std::uint64_t steps8 = 0, steps4 = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const TestRay& ray = rays[i];
    const co_vec3 org = v3(ray.org.x, ray.org.y, ray.org.z), dir = v3(ray.dir.x, ray.dir.y, ray.dir.z);
    std::uint32_t s8 = 0, s4 = 0;
    const HitOut k = kd_trace(&kv, org, dir, 0.f, kInf, 0);
    const HitOut b = bvh8_trace_steps(&bv, org, dir, 0.f, kInf, 0, &s8);
    const HitOut f = bvh4_trace_steps(&b4, org, dir, 0.f, kInf, 0, &s4);
    steps8 += s8;
    steps4 += s4;
    hits += k.triangle != HIT_NONE;
    differ += std::memcmp(&k, &b, sizeof(HitOut)) != 0;
    differ4 += std::memcmp(&f, &b, sizeof(HitOut)) != 0;
    if (i % 8 == 0) {
      const HitOut e = brute_force(kept, ray, 0.f, kInf);
      brute_differ += std::memcmp(&e, &b, sizeof(HitOut)) != 0;
    }
    for (const float limit : {0.5f, 1.5f}) {
      const float tmax = k.triangle != HIT_NONE ? limit * k.t : kInf;
      occlusion_differ += (kd_trace(&kv, org, dir, 0.f, tmax, 1).triangle != HIT_NONE) !=
                          (bvh8_trace_steps(&bv, org, dir, 0.f, tmax, 1, nullptr).triangle != HIT_NONE);
    }
  }
  fmt::print("[{}] {} rays, {} hits; 8-wide BVH {} nodes depth {}: {} closest hits differ from the KD-tree's, {} from "
             "the 4-wide BVH's, {} from brute force's, {} any-hit answers; {:.1f} nodes + triangles per ray (4-wide: "
             "{:.1f} nodes + leaves)\n",
             name, rays.size(), hits, bvh.stats.node_count, bvh.stats.depth, differ, differ4, brute_differ,
             occlusion_differ, double(steps8) / rays.size(), double(steps4) / rays.size());
  EXPECT_GT(hits, rays.size() / 4);
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(differ4, 0u);
  EXPECT_EQ(brute_differ, 0u);
  EXPECT_EQ(occlusion_differ, 0u);
}

TEST(Bvh8, GivesEveryTreesHitsBitForBit) {
  expect_same_hits(coplanar_grid(100, 100), "20k coplanar");
  expect_same_hits(random_soup(4000, 7), "soup");
  expect_same_hits(load_shipped("voxel-terrain.gltf"), "voxel terrain");
  for (const char* model : {"bunny/bun_zipper_res2.ply", "cornell-box-mcguire/CornellBox-Original.obj"})
    if (const auto positions = load_shared(model)) expect_same_hits(*positions, model);
}

// Far from the origin, boxes are small against their coordinates (a float's step at 1e5 is 2^-7, and
// the leaves' boxes span a few hundred steps at most): the grid's exponent must rise until every
// plane is a float, and the boxes must still hold their triangles.
TEST(Bvh8, QuantisesSmallBoxesFarFromTheOrigin) {
  std::vector<glm::vec3> positions = random_soup(2000, 11);
  for (glm::vec3& p : positions) p = p * 100.0f + glm::vec3(3.0e4f, -7.0e3f, 1.0e5f);
  expect_same_hits(positions, "far soup");
}

TEST(Bvh8, SameTreeForAnyThreadCount) {
  const KdTree kept = kept_triangles(random_soup(20'000, 3));
  const Bvh8 many = build_bvh8(kept.triangles);
  tbb::task_arena one(1);
  const Bvh8 single = one.execute([&] { return build_bvh8(kept.triangles); });
  ASSERT_EQ(many.nodes.size(), single.nodes.size());
  EXPECT_EQ(0, std::memcmp(many.nodes.data(), single.nodes.data(), many.nodes.size() * sizeof(Bvh8Node)));
  ASSERT_EQ(many.leaf_vertices.size(), single.leaf_vertices.size());
  EXPECT_EQ(0, std::memcmp(many.leaf_vertices.data(), single.leaf_vertices.data(),
                           many.leaf_vertices.size() * sizeof(Triangle)));
  EXPECT_TRUE(structure_errors(many, kept).empty());
  EXPECT_EQ(many.stats.sah_cost, single.stats.sah_cost);
  EXPECT_EQ(many.stats.leaf_count, single.stats.leaf_count);
  EXPECT_EQ(many.stats.depth, single.stats.depth);
}

// The octant order: a ray along the diagonal of octant s meets, of a node's children, first the one
// the builder put in slot s, when the children are well apart (eight cubes at a cube's corners).
TEST(Bvh8, SlotsFollowTheRaysOctant) {
  std::vector<glm::vec3> positions;
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 4; ++k) {  // four small triangles per corner: each corner a subtree
      const glm::vec3 o(c & 1 ? 10.f : 0.f, c & 2 ? 10.f : 0.f, c & 4 ? 10.f : 0.f);
      const glm::vec3 d(0.1f * k, 0.f, 0.f);
      positions.insert(positions.end(), {o + d, o + d + glm::vec3(1, 0, 0), o + d + glm::vec3(0, 1, 1)});
    }
  const KdTree kept = kept_triangles(positions);
  const Bvh8 bvh = build_bvh8(kept.triangles);
  for (const std::string& e : structure_errors(bvh, kept)) ADD_FAILURE() << e;
  const Bvh8Node& root = bvh.nodes[0];
  for (int s = 0; s < 8; ++s) {
    ASSERT_NE(meta_of(root, s), 0u) << "slot " << s;
    // slot s's box centre is the corner nearest along the direction with the signs of s
    const std::array<float, 6> box = bvh8_child_box(root, s);
    for (int a = 0; a < 3; ++a) {
      const float centre = 0.5f * (box[a] + box[a + 3]);
      EXPECT_EQ(centre < 5.f, !((s >> a) & 1)) << "slot " << s << " axis " << a;
    }
  }
}

// Where a binned build has nothing to bin (one triangle; 1000 copies of one, every centroid in one
// point; centroids halving their distance each time): shallow trees, and through the copies the
// first copy's hit (the least index at equal t).
TEST(Bvh8, DegenerateInputsStayShallowAndFindTheLowestIndex) {
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
    const Bvh8 bvh = build_bvh8(kept.triangles);
    for (const std::string& e : structure_errors(bvh, kept)) ADD_FAILURE() << e;
  }
  const KdTree kept = kept_triangles(copies);
  const Bvh8 bvh = build_bvh8(kept.triangles);
  const Bvh8View view = host_view(bvh);
  const HitOut hit = bvh8_trace_steps(&view, v3(0.2f, 0.2f, 0.f), v3(0.f, 0.f, 1.f), 0.f, kInf, 0, nullptr);
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_EQ(hit.t, 1.0f);
}

// As Bvh4.ARayWithANanDirectionMisses: a NaN direction component misses instead of walking out of
// the arrays (the two trees share bvh4_inverse).
TEST(Bvh8, ARayWithANanDirectionMisses) {
  const KdTree kept = kept_triangles(random_soup(4000, 7));
  const Bvh8 bvh = build_bvh8(kept.triangles);
  const Bvh8View view = host_view(bvh);
  EXPECT_NE(bvh8_trace_steps(&view, v3(0.f, 0.f, 0.f), v3(0.f, 0.f, 1.f), 0.f, kInf, 0, nullptr).triangle, HIT_NONE);
  const float nan = std::nanf("");
  for (const co_vec3 dir : {v3(nan, 0.f, 1.f), v3(0.f, nan, 0.f), v3(nan, nan, nan), v3(0.3f, -0.2f, nan)})
    for (const int any_hit : {0, 1})
      EXPECT_EQ(bvh8_trace_steps(&view, v3(0.f, 0.f, 0.f), dir, 0.f, kInf, any_hit, nullptr).triangle, HIT_NONE);
}

TEST(Bvh8, RejectsAnEmptyInput) {
  EXPECT_THROW(build_bvh8({}), InputError);
}

}  // namespace
}  // namespace cohort::test
