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

}  // namespace

Bounds clip_triangle_bounds(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            const Bounds& box) {
  Polygon poly;
  poly.v[0] = glm::dvec3(a);
  poly.v[1] = glm::dvec3(b);
  poly.v[2] = glm::dvec3(c);
  poly.n = 3;
  // A plane that no vertex lies beyond leaves the polygon as it is: only the planes that cut the
  // triangle (usually one or two of the six) are worth a pass.
  const glm::vec3 tri_lo = glm::min(a, glm::min(b, c)), tri_hi = glm::max(a, glm::max(b, c));
  Polygon scratch;
  Polygon* cur = &poly;
  Polygon* next = &scratch;
  auto clip = [&](int axis, double plane, double sign) {
    clip_plane(*cur, axis, plane, sign, *next);
    std::swap(cur, next);
  };
  for (int axis = 0; axis < 3 && cur->n > 0; ++axis) {
    if (tri_lo[axis] < box.lo[axis]) clip(axis, box.lo[axis], 1.0);
    if (cur->n > 0 && tri_hi[axis] > box.hi[axis]) clip(axis, box.hi[axis], -1.0);
  }
  Bounds result;
  if (cur->n == 0) return result;
  glm::dvec3 lo(std::numeric_limits<double>::infinity());
  glm::dvec3 hi(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < cur->n; ++i) {
    lo = glm::min(lo, cur->v[i]);
    hi = glm::max(hi, cur->v[i]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    result.lo[axis] = std::max(round_down(lo[axis]), box.lo[axis]);
    result.hi[axis] = std::min(round_up(hi[axis]), box.hi[axis]);
    if (result.lo[axis] > result.hi[axis]) return Bounds{};  // only a rounding sliver was left
  }
  return result;
}

}  // namespace cohort::kd
