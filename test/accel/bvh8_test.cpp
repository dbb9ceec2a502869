// The compressed 8-wide BVH's layout (runtime/accel/bvh8.h): its structure check (decoded child boxes
// around their subtrees and exact with or without fma), the quantisation far from the origin and the
// octant order of its slots. The checks it shares with the other wide BVHs (every ray's hit bit for
// bit against the KD-tree's and the other trees', the same tree for any thread count, degenerate
// inputs) run on it in wide_bvh_common_test.cpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "accel/test_meshes.h"
#include "accel/wide_bvh_check.h"
#include "kernels/common/accel/bvh8_traverse.h"
#include "runtime/util/error.h"

namespace cohort::test {
namespace {

std::uint32_t meta_of(const Bvh8Node& n, int slot) { return ((slot < 4 ? n.index.z : n.index.w) >> (8 * (slot % 4))) & 255u; }

}  // namespace

// Walks the tree from the root (with StructureTally's checks): each node where its parent's child
// base and imask put it; every used slot's decoded box exact in float whether or not the multiply-add
// is fused; inner slots' meta; leaves of 1-3 triangles within the node's 24 offsets, no offset
// shared; unused slots with meta 0; no node without children.
std::vector<std::string> structure_errors(const Bvh8& bvh, const KdTree& kept) {
  StructureTally tally(bvh.nodes.size(), bvh.leaf_vertices, kept);
  std::vector<std::string>& errors = tally.errors;
  std::function<void(std::uint32_t, int, const std::array<float, 6>*)> walk = [&](std::uint32_t index, int depth,
                                                                                  const std::array<float, 6>* parent) {
    if (!tally.reach(index, depth)) return;
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
      tally.box(index, s, box.data(), box.data() + 3, parent ? parent->data() : nullptr,
                parent ? parent->data() + 3 : nullptr);
      if (imask & (1u << s)) {
        if (m != 0x20u + 24u + s) errors.push_back(fmt::format("node {} slot {}: inner meta {:#x}", index, s, m));
        const std::uint32_t child = n.index.x + std::popcount(imask & ((1u << s) - 1u));
        walk(child, depth + 1, &box);
        continue;
      }
      const std::uint32_t count = std::popcount(m >> 5), offset = m & 31u;
      if ((m >> 5) != (1u << count) - 1u || count == 0 || offset + count > 24) {
        errors.push_back(fmt::format("node {} slot {}: leaf meta {:#x}", index, s, m));
        continue;
      }
      const std::uint32_t bits = ((1u << count) - 1u) << offset;
      if (used_offsets & bits) errors.push_back(fmt::format("node {} slot {}: triangle offsets shared", index, s));
      used_offsets |= bits;
      tally.leaf(n.index.y + offset, count, BVH8_LEAF_MAX, box.data(), box.data() + 3);
    }
    if (children == 0) errors.push_back(fmt::format("node {} has no children", index));
  };
  walk(0, 1, nullptr);
  return tally.finish(bvh.stats, BVH8_STACK);
}

namespace {

// Far from the origin, boxes are small against their coordinates (a float's step at 1e5 is 2^-7, and
// the leaves' boxes span a few hundred steps at most): the grid's exponent must rise until every
// plane is a float, and the boxes must still hold their triangles.
TEST(Bvh8, QuantisesSmallBoxesFarFromTheOrigin) {
  std::vector<glm::vec3> positions = random_soup(2000, 11);
  for (glm::vec3& p : positions) p = p * 100.0f + glm::vec3(3.0e4f, -7.0e3f, 1.0e5f);
  expect_same_hits<Bvh8Traits>(positions, "far soup");
}

// The node test's slab distances (bvh8_grid, then q * step + offset) bound the exact ones, (origin +
// q 2^e - o) * inverse in double, from the safe side before the last rounding: an entry distance never
// above the exact one rounded up, an exit never below it rounded down, fused (as the host and most
// devices run it) and unfused (two roundings, as NVIDIA's OpenCL and Oclgrind run it). Rays from near
// and far origins, grids from fine to coarse, nodes near to and far from the origin.
TEST(Bvh8, NodeTestBoundsTheExactSlabDistances) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  std::uniform_int_distribution<int> exponent(-24, 12), byte(0, 255), scale_pow(-3, 18);
  auto up = [](double x) {
    float f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
  };
  auto down = [](double x) {
    float f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
  };
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const float node_scale = std::ldexp(1.f, scale_pow(rng)), ray_scale = std::ldexp(1.f, scale_pow(rng));
    co_uint4 h{};
    std::array<int, 3> e{};
    std::array<float, 3> origin{};
    for (int a = 0; a < 3; ++a) {
      e[a] = exponent(rng);
      origin[a] = std::ldexp(std::floor(std::ldexp(unit(rng) * node_scale, -e[a])), e[a]);
    }
    h.x = co_as_uint(origin[0]); h.y = co_as_uint(origin[1]); h.z = co_as_uint(origin[2]);
    h.w = std::uint32_t(e[0] + 127) | std::uint32_t(e[1] + 127) << 8 | std::uint32_t(e[2] + 127) << 16;
    co_vec3 org = v3(unit(rng) * ray_scale, unit(rng) * ray_scale, unit(rng) * ray_scale);
    co_vec3 dir = v3_normalize(v3(unit(rng), unit(rng), unit(rng)));
    if (trial % 7 == 0) dir.y = 0.f;  // an axis-parallel ray: inverse 1e18
    const Bvh8Ray r = bvh8_ray(org, dir);
    const Bvh8Grid g = bvh8_grid(&r, h);
    const float o[3] = {r.o.x, r.o.y, r.o.z}, inv[3] = {r.inv.x, r.inv.y, r.inv.z};
    const float step[3] = {g.step.x, g.step.y, g.step.z}, near[3] = {g.near.x, g.near.y, g.near.z};
    const float far[3] = {g.far.x, g.far.y, g.far.z};
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 4; ++k) {
        const int q = k < 2 ? k * 255 : byte(rng);
        const double exact = (double(origin[a]) + std::ldexp(double(q), e[a]) - double(o[a])) * double(inv[a]);
        // fused: the kernel's own BVH8_PLANE_T (the host builds its fused form), q in the word's first
        // byte; unfused: that macro's other form, a multiply and an add
        const float fused_near = BVH8_PLANE_T(std::uint32_t(q), step[a], near[a]).x;
        const float fused_far = BVH8_PLANE_T(std::uint32_t(q), step[a], far[a]).x;
        const float unfused_near = float(q) * step[a] + near[a], unfused_far = float(q) * step[a] + far[a];
        ASSERT_LE(fused_near, up(exact)) << "trial " << trial << " axis " << a << " q " << q;
        ASSERT_LE(unfused_near, up(exact)) << "trial " << trial << " axis " << a << " q " << q;
        ASSERT_GE(fused_far, down(exact)) << "trial " << trial << " axis " << a << " q " << q;
        ASSERT_GE(unfused_far, down(exact)) << "trial " << trial << " axis " << a << " q " << q;
        ++checked;
      }
  }
  EXPECT_EQ(checked, 20000 * 12);
  // bvh_slab_ray's non-finite origin: every plane at +infinity, none NaN, so no box is entered
  const Bvh8Ray lost = bvh8_ray(v3(INFINITY, 0.f, 0.f), v3(0.f, 0.f, 1.f));
  co_uint4 h{};
  h.w = 127u | 127u << 8 | 127u << 16;
  const Bvh8Grid g = bvh8_grid(&lost, h);
  for (float q : {0.f, 255.f}) {
    EXPECT_EQ(std::fma(q, g.step.x, g.near.x), INFINITY);
    EXPECT_EQ(q * g.step.z + g.far.z, INFINITY);
  }
}

// Beyond 1e19 from the origin the node test's products could overflow: the build refuses such a
// scene with an input error rather than trace it wrongly; at the bound it builds.
TEST(Bvh8, RefusesVerticesBeyondItsBound) {
  std::vector<glm::vec3> near = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1e19f, 0, 0}, {-1e19f, 1, 0}, {-1e19f, 0, 1}};
  EXPECT_NO_THROW(build_bvh8(kept_triangles(near).triangles));
  std::vector<glm::vec3> far = near;
  far[4].y = 3e19f;
  EXPECT_THROW(build_bvh8(kept_triangles(far).triangles), InputError);
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

}  // namespace
}  // namespace cohort::test
