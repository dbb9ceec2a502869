// Sutherland-Hodgman clipping of a triangle against the six planes of a box.
#include "runtime/accel/clip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace cohort::kd {
namespace {

// A triangle clipped by 6 planes has at most 3 + 6 vertices.
constexpr std::size_t kMaxVertices = 9;

struct Polygon {
  std::array<glm::dvec3, kMaxVertices> v;
  std::size_t n = 0;
};

// Keeps the part of `in` with sign * (p[axis] - plane) >= 0. Points on the plane count as inside,
// so a triangle lying in a cell face survives (it belongs to that cell too).
Polygon clip_plane(const Polygon& in, int axis, double plane, double sign) {
  Polygon out;
  for (std::size_t i = 0; i < in.n; ++i) {
    const glm::dvec3& cur = in.v[i];
    const glm::dvec3& next = in.v[(i + 1) % in.n];
    const double dc = sign * (cur[axis] - plane);
    const double dn = sign * (next[axis] - plane);
    if (dc >= 0.0) out.v[out.n++] = cur;
    if ((dc >= 0.0) != (dn >= 0.0)) {
      glm::dvec3 p = cur + (next - cur) * (dc / (dc - dn));
      p[axis] = plane;  // exactly on the plane, whatever the rounding of the interpolation
      out.v[out.n++] = p;
    }
  }
  return out;
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
  for (int axis = 0; axis < 3 && poly.n > 0; ++axis) {
    poly = clip_plane(poly, axis, box.lo[axis], 1.0);
    if (poly.n > 0) poly = clip_plane(poly, axis, box.hi[axis], -1.0);
  }
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

}  // namespace cohort::kd
