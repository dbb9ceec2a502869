// Sutherland-Hodgman clipping of a triangle against the six planes of a box.
#include "runtime/accel/clip.h"

#include <algorithm>
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
  out.n = 0;
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
      out.v[out.n++] = p;
    }
    if (d_cur >= 0.0) out.v[out.n++] = cur;
    prev = &cur;
    d_prev = d_cur;
  }
}

float round_down(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity())
                                    : f;
}

float round_up(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

Polygon triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  Polygon poly;
  poly.v[0] = glm::dvec3(a);
  poly.v[1] = glm::dvec3(b);
  poly.v[2] = glm::dvec3(c);
  poly.n = 3;
  return poly;
}

// The triangle clipped to `box`. A plane that no vertex lies beyond leaves the polygon as it is:
// only the planes that cut the triangle (usually one or two of the six) are worth a pass.
Polygon clip_to_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const Bounds& box) {
  const glm::vec3 tri_lo = glm::min(a, glm::min(b, c)), tri_hi = glm::max(a, glm::max(b, c));
  std::array<Polygon, 2> poly{triangle(a, b, c), Polygon{}};
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

// The polygon's bounds rounded outward to float and clamped to `box`; empty when nothing is left.
Bounds bounds_within(const Polygon& poly, const Bounds& box) {
  Bounds result;
  if (poly.n == 0) return result;
  glm::dvec3 lo(std::numeric_limits<double>::infinity());
  glm::dvec3 hi(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < poly.n; ++i) {
    lo = glm::min(lo, poly.v[i]);
    hi = glm::max(hi, poly.v[i]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    result.lo[axis] = std::max(round_down(lo[axis]), box.lo[axis]);
    result.hi[axis] = std::min(round_up(hi[axis]), box.hi[axis]);
    if (result.lo[axis] > result.hi[axis]) return Bounds{};  // only a rounding sliver was left
  }
  return result;
}

}  // namespace

Bounds clip_triangle_bounds(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            const Bounds& box) {
  return bounds_within(clip_to_box(a, b, c, box), box);
}

std::array<Bounds, 2> split_triangle_bounds(const glm::vec3& a, const glm::vec3& b,
                                            const glm::vec3& c, const Bounds& cell, int axis,
                                            float pos) {
  const Polygon inside = clip_to_box(a, b, c, cell);
  std::array<Bounds, 2> children{cell, cell};
  children[0].hi[axis] = pos;
  children[1].lo[axis] = pos;
  std::array<Polygon, 2> side;
  if (inside.n == 0) return {Bounds{}, Bounds{}};
  clip_plane(inside, axis, pos, -1.0, side[0]);
  clip_plane(inside, axis, pos, 1.0, side[1]);
  return {bounds_within(side[0], children[0]), bounds_within(side[1], children[1])};
}

}  // namespace cohort::kd
