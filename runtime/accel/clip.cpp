// Sutherland-Hodgman clipping of a triangle against the six planes of a box.
#include "runtime/accel/clip.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace cohort::kd {
namespace {

// A triangle clipped by 6 planes has at most 3 + 6 vertices.
constexpr std::size_t kMaxVertices = 9;

struct Polygon {
  std::array<glm::dvec3, kMaxVertices> v;
  std::size_t n = 0;
};

// Keeps the part of `in` with sign * (p[axis] - plane) >= 0, written to `out`. Points on the plane
// count as inside, so a triangle lying in a cell face survives (it belongs to that cell too).
void clip_plane(const Polygon& in, int axis, double plane, double sign, Polygon& out) {
  std::size_t n = 0;  // not out.n: a count kept in memory made each vertex wait for the one before
  const glm::dvec3* prev = &in.v[in.n - 1];
  double d_prev = sign * ((*prev)[axis] - plane);
  for (std::size_t i = 0; i < in.n; ++i) {
    const glm::dvec3& cur = in.v[i];
    const double d_cur = sign * (cur[axis] - plane);
    // The edge prev -> cur: its crossing, then cur when inside (the same output as walking
    // cur -> next, rotated by one vertex).
    if ((d_prev >= 0.0) != (d_cur >= 0.0)) {
      glm::dvec3 p = *prev + (cur - *prev) * (d_prev / (d_prev - d_cur));
      p[axis] = plane;  // exactly on the plane, whatever the rounding of the interpolation
      out.v[n++] = p;
    }
    if (d_cur >= 0.0) out.v[n++] = cur;
    prev = &cur;
    d_prev = d_cur;
  }
  out.n = n;
}

// The next float below / above f, as std::nextafter towards -inf / +inf gives it, from its bits
// (inline: std::nextafter is a call into libm, and the clip rounds six bounds per child).
float next_down(float f) {
  if (f == 0.f) return -std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.f ? bits - 1u : bits + 1u);
}

float next_up(float f) {
  if (f == 0.f) return std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.f ? bits + 1u : bits - 1u);
}

float round_down(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) > x ? next_down(f) : f;
}

float round_up(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) < x ? next_up(f) : f;
}

// The triangle clipped to `box`, in one of `poly` (the other is working memory; neither is
// cleared or copied: the clipping runs for every straddling reference of the KD build). A plane
// that no vertex lies beyond leaves the polygon as it is: only the planes that cut the triangle
// (usually one or two of the six) are worth a pass.
const Polygon& clip_to_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                           const Bounds& box, std::array<Polygon, 2>& poly) {
  const glm::vec3 tri_lo = glm::min(a, glm::min(b, c)), tri_hi = glm::max(a, glm::max(b, c));
  poly[0].v[0] = glm::dvec3(a);
  poly[0].v[1] = glm::dvec3(b);
  poly[0].v[2] = glm::dvec3(c);
  poly[0].n = 3;
  int cur = 0;
  auto clip = [&](int axis, double plane, double sign) {
    clip_plane(poly[cur], axis, plane, sign, poly[1 - cur]);
    cur = 1 - cur;
  };
  for (int axis = 0; axis < 3 && poly[cur].n > 0; ++axis) {
    if (tri_lo[axis] < box.lo[axis]) clip(axis, box.lo[axis], 1.0);
    if (poly[cur].n > 0 && tri_hi[axis] > box.hi[axis]) clip(axis, box.hi[axis], -1.0);
  }
  return poly[cur];
}

// The double-precision bounds of a set of points, taken in the order given (glm::min keeps the
// first of equal values, so the order matters for -0 and +0; this keeps the polygon's order).
struct PointBounds {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  bool any = false;

  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    any = true;
  }
};

// The points' bounds rounded outward to float and clamped to `box`; empty when there are none.
Bounds bounds_within(const PointBounds& points, const Bounds& box) {
  Bounds result;
  if (!points.any) return result;
  for (int axis = 0; axis < 3; ++axis) {
    result.lo[axis] = std::max(round_down(points.lo[axis]), box.lo[axis]);
    result.hi[axis] = std::min(round_up(points.hi[axis]), box.hi[axis]);
    if (result.lo[axis] > result.hi[axis]) return Bounds{};  // only a rounding sliver was left
  }
  return result;
}

Bounds bounds_within(const Polygon& poly, const Bounds& box) {
  PointBounds points;
  for (std::size_t i = 0; i < poly.n; ++i) points.add(poly.v[i]);
  return bounds_within(points, box);
}

// clip_plane(in, axis, plane, -1.0) and clip_plane(in, axis, plane, 1.0) at once, keeping only the
// bounds of the points each would output, in the same order: the same boxes without writing the
// two polygons.
std::array<PointBounds, 2> split_bounds(const Polygon& in, int axis, double plane) {
  std::array<PointBounds, 2> out;
  constexpr std::array<double, 2> kSign{-1.0, 1.0};
  const glm::dvec3* prev = &in.v[in.n - 1];
  std::array<double, 2> d_prev{kSign[0] * ((*prev)[axis] - plane),
                               kSign[1] * ((*prev)[axis] - plane)};
  for (std::size_t i = 0; i < in.n; ++i) {
    const glm::dvec3& cur = in.v[i];
    for (int side = 0; side < 2; ++side) {
      const double d_cur = kSign[side] * (cur[axis] - plane);
      if ((d_prev[side] >= 0.0) != (d_cur >= 0.0)) {
        glm::dvec3 p = *prev + (cur - *prev) * (d_prev[side] / (d_prev[side] - d_cur));
        p[axis] = plane;
        out[side].add(p);
      }
      if (d_cur >= 0.0) out[side].add(cur);
      d_prev[side] = d_cur;
    }
    prev = &cur;
  }
  return out;
}

}  // namespace

Bounds clip_triangle_bounds(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            const Bounds& box) {
  std::array<Polygon, 2> poly;
  return bounds_within(clip_to_box(a, b, c, box, poly), box);
}

std::array<Bounds, 2> split_triangle_bounds(const glm::vec3& a, const glm::vec3& b,
                                            const glm::vec3& c, const Bounds& cell, int axis,
                                            float pos) {
  std::array<Polygon, 2> poly;
  const Polygon& inside = clip_to_box(a, b, c, cell, poly);
  std::array<Bounds, 2> children{cell, cell};
  children[0].hi[axis] = pos;
  children[1].lo[axis] = pos;
  if (inside.n == 0) return {Bounds{}, Bounds{}};
  const std::array<PointBounds, 2> side = split_bounds(inside, axis, pos);
  return {bounds_within(side[0], children[0]), bounds_within(side[1], children[1])};
}

}  // namespace cohort::kd
