#include "runtime/accel/clip.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace cohort::kd
