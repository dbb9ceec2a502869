#include "runtime/accel/clip.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "runtime/accel/x86_dispatch.h"

namespace cohort::kd {
namespace {

Bounds box(glm::vec3 lo, glm::vec3 hi) {
  Bounds b;
  b.lo = lo;
  b.hi = hi;
  return b;
}

TEST(Clip, TriangleInsideKeepsItsBounds) {
  const Bounds b = clip_triangle_bounds({0.1f, 0.1f, 0.1f}, {0.9f, 0.2f, 0.3f}, {0.5f, 0.8f, 0.6f},
                                        box(glm::vec3(0.f), glm::vec3(1.f)));
  EXPECT_EQ(b.lo, glm::vec3(0.1f, 0.1f, 0.1f));
  EXPECT_EQ(b.hi, glm::vec3(0.9f, 0.8f, 0.6f));
}

TEST(Clip, DiagonalTriangleIsCutToTheBox) {
  // The triangle (0,0)-(2,0)-(0,2) in z = 0.5 against [1,2]x[0,2]: the part x >= 1 has y <= 1.
  const Bounds b =
      clip_triangle_bounds({0, 0, 0.5f}, {2, 0, 0.5f}, {0, 2, 0.5f}, box({1, 0, 0}, {2, 2, 1}));
  EXPECT_FLOAT_EQ(b.lo.x, 1.f);
  EXPECT_FLOAT_EQ(b.hi.x, 2.f);
  EXPECT_FLOAT_EQ(b.lo.y, 0.f);
  EXPECT_FLOAT_EQ(b.hi.y, 1.f);
  EXPECT_EQ(b.lo.z, 0.5f);
  EXPECT_EQ(b.hi.z, 0.5f);
}

TEST(Clip, TriangleMissingTheBoxCornerIsEmpty) {
  // Its bounding box overlaps [1.5,2]^2 but the triangle (below x + y = 2) does not.
  EXPECT_TRUE(
      clip_triangle_bounds({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, box({1.5f, 1.5f, -1}, {2, 2, 1}))
          .empty());
}

TEST(Clip, TriangleInAFaceSurvives) {
  const Bounds b =
      clip_triangle_bounds({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, box(glm::vec3(0.f), glm::vec3(1.f)));
  ASSERT_FALSE(b.empty());
  EXPECT_EQ(b.lo.z, 1.f);
  EXPECT_EQ(b.hi.z, 1.f);
}

TEST(Clip, ResultIsConservativeAndInsideTheBox) {
  // An awkward slope: the exact cut is not representable, so the box must round outward.
  const glm::vec3 a(0.1f, 0.3f, 0.7f), b(0.9f, 0.35f, 0.1f), c(0.2f, 0.95f, 0.4f);
  const Bounds cell = box({0.33f, 0.f, 0.f}, {1.f, 1.f, 1.f});
  const Bounds r = clip_triangle_bounds(a, b, c, cell);
  ASSERT_FALSE(r.empty());
  EXPECT_GE(r.lo.x, cell.lo.x);
  EXPECT_LE(r.hi.y, cell.hi.y);
  // Points of the triangle inside the cell lie inside the result.
  for (float u = 0.f; u <= 1.f; u += 0.0625f) {
    for (float v = 0.f; u + v <= 1.f; v += 0.0625f) {
      const glm::dvec3 p =
          glm::dvec3(a) + double(u) * glm::dvec3(b - a) + double(v) * glm::dvec3(c - a);
      if (p.x < cell.lo.x) continue;
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_GE(p[axis], double(r.lo[axis]) - 1e-7);
        EXPECT_LE(p[axis], double(r.hi[axis]) + 1e-7);
      }
    }
  }
}

TEST(Clip, SplitGivesTheBoundsOfEachHalf) {
  // split_triangle_bounds clips to the cell once and then to each side of the plane; the boxes
  // must be those of clipping to each half on its own (to rounding), and empty on the same sides:
  // with the cell as the extent (every face the triangle crosses clipped), and with the triangle's
  // own bounds in the cell, as a KD reference's box gives them (the faces those stay clear of
  // skipped).
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.f, 2.f);
  const Bounds cell = box(glm::vec3(0.f), glm::vec3(1.f));
  int straddling = 0, tighter = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const int axis = trial % 3;
    const float pos = 0.1f + 0.8f * static_cast<float>(trial % 7) / 6.f;
    const Bounds part = clip_triangle_bounds(a, b, c, cell);
    std::array<Bounds, 2> halves{cell, cell};
    halves[0].hi[axis] = pos;
    halves[1].lo[axis] = pos;
    for (const Bounds& extent : {cell, part.empty() ? cell : part}) {
      const std::array<Bounds, 2> split = split_triangle_bounds(a, b, c, cell, extent, axis, pos);
      for (int side = 0; side < 2; ++side) {
        SCOPED_TRACE(testing::Message() << "trial " << trial << " side " << side);
        const Bounds alone = clip_triangle_bounds(a, b, c, halves[side]);
        ASSERT_EQ(split[side].empty(), alone.empty());
        if (alone.empty()) continue;
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(split[side].lo[k], alone.lo[k], 1e-6f);
          EXPECT_NEAR(split[side].hi[k], alone.hi[k], 1e-6f);
          EXPECT_GE(split[side].lo[k], halves[side].lo[k]);
          EXPECT_LE(split[side].hi[k], halves[side].hi[k]);
        }
      }
      straddling += !split[0].empty() && !split[1].empty();
    }
    for (int k = 0; k < 3 && !part.empty(); ++k) {
      tighter += (part.lo[k] > cell.lo[k] && std::min({a[k], b[k], c[k]}) < cell.lo[k]) +
                 (part.hi[k] < cell.hi[k] && std::max({a[k], b[k], c[k]}) > cell.hi[k]);
    }
  }
  EXPECT_GT(straddling, 400) << "the trials must exercise triangles cut by the plane";
  EXPECT_GT(tighter, 200) << "the trials must exercise faces the triangle crosses outside the cell";
}

TEST(Clip, VectorSplitMatchesPortableBitForBit) {
  // The KD build's results are the same bits on every machine only if the AVX2 split equals the
  // portable one exactly. Coordinates from a small grid (with -0 and +0, so the order of equal
  // minima shows) make vertices lie on cell faces and on the plane, flat and sliver triangles;
  // the smallest denormals make crossings that round to zero in float; random coordinates make
  // awkward slopes and crossings that round.
#if COHORT_X86_DISPATCH
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "no AVX2 on this CPU: only one version";
#else
  GTEST_SKIP() << "no vector version in this build";
#endif
  constexpr float kTiny = std::numeric_limits<float>::denorm_min();
  const std::array<float, 12> grid{-1.f,  -0.5f, -kTiny, -0.f, 0.f, kTiny,
                                   0.25f, 1.f / 3.f, 0.5f, 0.7f, 1.f, 1.5f};
  const std::array<float, 8> tiny{-3 * kTiny, -2 * kTiny, -kTiny, -0.f,
                                  0.f,        kTiny,      2 * kTiny, 3 * kTiny};
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, 11);
  std::uniform_real_distribution<float> any(-1.2f, 1.7f);
  // Kind 0: the grid; 1: multiples of the smallest denormal, whose crossings round to zero or
  // to a denormal in float; 2: random.
  auto coordinate = [&](int kind) {
    const std::size_t i = pick(rng);
    return kind == 0 ? grid[i] : kind == 1 ? tiny[i % tiny.size()] : any(rng);
  };
  int compared = 0, straddling = 0;
  for (int trial = 0; trial < 300000; ++trial) {
    const int kind = trial % 3;
    glm::vec3 v[3];
    for (glm::vec3& p : v) p = {coordinate(kind), coordinate(kind), coordinate(kind)};
    Bounds cell;
    for (int k = 0; k < 3; ++k) {
      float lo = coordinate(kind), hi = coordinate(kind);
      if (hi < lo) std::swap(lo, hi);
      if (!(lo < hi)) hi = lo + 0.5f;
      cell.lo[k] = lo;
      cell.hi[k] = hi;
    }
    const int axis = (trial / 3) % 3;
    const float lo = cell.lo[axis], hi = cell.hi[axis];
    float pos = coordinate(kind);
    if (!(pos > lo && pos < hi)) pos = lo + (hi - lo) * 0.5f;
    if (!(pos > lo && pos < hi)) continue;
    // The extent reaches each face or stops one step short of it (that face is then skipped).
    Bounds extent = cell;
    for (int k = 0; k < 3; ++k) {
      const float inside_lo = std::nextafter(cell.lo[k], cell.hi[k]);
      const float inside_hi = std::nextafter(cell.hi[k], cell.lo[k]);
      if (rng() % 3 == 0 && inside_lo <= inside_hi) extent.lo[k] = inside_lo;
      if (rng() % 3 == 0 && extent.lo[k] <= inside_hi) extent.hi[k] = inside_hi;
    }
    const std::array<Bounds, 2> fast =
        split_triangle_bounds(v[0], v[1], v[2], cell, extent, axis, pos);
    const std::array<Bounds, 2> portable =
        split_triangle_bounds_portable(v[0], v[1], v[2], cell, extent, axis, pos);
    for (int side = 0; side < 2; ++side) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(std::bit_cast<std::uint32_t>(fast[side].lo[k]),
                  std::bit_cast<std::uint32_t>(portable[side].lo[k]))
            << "trial " << trial << " side " << side << " axis " << k;
        ASSERT_EQ(std::bit_cast<std::uint32_t>(fast[side].hi[k]),
                  std::bit_cast<std::uint32_t>(portable[side].hi[k]))
            << "trial " << trial << " side " << side << " axis " << k;
      }
    }
    ++compared;
    straddling += !portable[0].empty() && !portable[1].empty();
  }
  EXPECT_GT(compared, 250000);
  EXPECT_GT(straddling, 30000) << "the trials must exercise triangles cut by the plane";
}

}  // namespace
}  // namespace cohort::kd
