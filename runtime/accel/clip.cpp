// Sutherland-Hodgman clipping of a triangle against the six planes of a box. The KD build clips
// every straddling reference (3.5M times for a 1.1M-triangle mesh, a fifth of its time), so on x86
// with AVX2 split_triangle_bounds runs a vector version of the same arithmetic (below).
#include "runtime/accel/clip.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "runtime/accel/x86_dispatch.h"

namespace cohort::kd {
namespace {

// A convex polygon gains at most one vertex per plane, so a triangle clipped by 6 planes has at
// most 3 + 6. Rounding can leave a clipped polygon very slightly non-convex, where a plane could in
// principle cross it more than twice: a pass has room for two points per input vertex (and one
// more, which the vector clip writes past the last point it keeps) and keeps at most
// kMaxVertices, so no input writes out of bounds.
constexpr std::size_t kMaxVertices = 9;
constexpr std::size_t kRoom = 2 * kMaxVertices + 1;

struct Polygon {
  std::array<glm::dvec3, kRoom> v;
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
  out.n = std::min(n, kMaxVertices);
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

// The faces of `box` whose planes can cut the triangle's part in it: where a vertex lies beyond
// the face and `extent` (containing that part) reaches the face. The triangle clipped by the other
// five planes is convex; had it points beyond a face as well as the part inside, it would have
// points on the face too, and so would the part. So a face the extent stays clear of cuts
// nothing, and its pass is skipped (18-22 % of the passes of the Sponza x4 and bunny x16 builds).
struct CutFaces {
  glm::bvec3 lo, hi;
};

inline CutFaces cut_faces(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                          const Bounds& box, const Bounds& extent) {
  const glm::vec3 tri_lo = glm::min(a, glm::min(b, c)), tri_hi = glm::max(a, glm::max(b, c));
  CutFaces cut;
  for (int k = 0; k < 3; ++k) {  // bitwise: no branch per face
    cut.lo[k] = (tri_lo[k] < box.lo[k]) & (extent.lo[k] <= box.lo[k]);
    cut.hi[k] = (tri_hi[k] > box.hi[k]) & (extent.hi[k] >= box.hi[k]);
  }
  return cut;
}

// The triangle clipped to `box`, in one of `poly` (the other is working memory; neither is
// cleared or copied: the clipping runs for every straddling reference of the KD build). Only the
// planes of cut_faces get a pass (usually one or two of the six): another plane leaves the
// polygon as it is.
const Polygon& clip_to_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                           const Bounds& box, const Bounds& extent, std::array<Polygon, 2>& poly) {
  const CutFaces cut = cut_faces(a, b, c, box, extent);
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
    if (cut.lo[axis]) clip(axis, box.lo[axis], 1.0);
    if (poly[cur].n > 0 && cut.hi[axis]) clip(axis, box.hi[axis], -1.0);
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
  return bounds_within(clip_to_box(a, b, c, box, box, poly), box);
}

#if COHORT_X86_DISPATCH
namespace avx2 {
std::array<Bounds, 2> split_triangle_bounds(const glm::vec3& a, const glm::vec3& b,
                                            const glm::vec3& c, const Bounds& cell,
                                            const Bounds& extent, int axis, float pos);
}  // namespace avx2
#endif

std::array<Bounds, 2> split_triangle_bounds(const glm::vec3& a, const glm::vec3& b,
                                            const glm::vec3& c, const Bounds& cell,
                                            const Bounds& extent, int axis, float pos) {
#if COHORT_X86_DISPATCH
  if (__builtin_cpu_supports("avx2")) {
    return avx2::split_triangle_bounds(a, b, c, cell, extent, axis, pos);
  }
#endif
  return split_triangle_bounds_portable(a, b, c, cell, extent, axis, pos);
}

std::array<Bounds, 2> split_triangle_bounds_portable(const glm::vec3& a, const glm::vec3& b,
                                                     const glm::vec3& c, const Bounds& cell,
                                                     const Bounds& extent, int axis, float pos) {
  std::array<Polygon, 2> poly;
  const Polygon& inside = clip_to_box(a, b, c, cell, extent, poly);
  std::array<Bounds, 2> children{cell, cell};
  children[0].hi[axis] = pos;
  children[1].lo[axis] = pos;
  if (inside.n == 0) return {Bounds{}, Bounds{}};
  const std::array<PointBounds, 2> side = split_bounds(inside, axis, pos);
  return {bounds_within(side[0], children[0]), bounds_within(side[1], children[1])};
}

#if COHORT_X86_DISPATCH
// split_triangle_bounds in AVX2: the same operations in the same order, so the same bits (checked
// against the portable version by Clip.VectorSplitMatchesPortableBitForBit). What makes it 1.8x
// faster (200-240 against 350-430 cycles a clip of the bunny x16 and Sponza x4 builds, replayed
// in cache): a point is one 4-lane vector, so setting its coordinate on the plane is a blend, not
// a store into memory that the next load of the whole point waits for; the axis is a template
// parameter; clipping writes every output point and keeps it by count; the two sides of the split
// share each crossing point (dp / (dp - dc) is the same bits for either sign); the bounds and
// their outward rounding take no branches.
#pragma GCC push_options
#pragma GCC target("avx2")
namespace avx2 {
namespace {

using Point = double __attribute__((vector_size(32)));  // x, y, z, unused
using Mask = std::int64_t __attribute__((vector_size(32)));
using Float4 = float __attribute__((vector_size(16)));
using Bits4 = std::uint32_t __attribute__((vector_size(16)));  // unsigned: steps wrap, no overflow
using Mask4 = std::int32_t __attribute__((vector_size(16)));

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Polygon {
  std::array<Point, kRoom> v;
  std::size_t n = 0;
};

Point point(const glm::vec3& p) { return Point{p.x, p.y, p.z, 0.0}; }

Mask all(bool b) {
  const std::int64_t m = -static_cast<std::int64_t>(b);
  return Mask{m, m, m, m};
}

// clip_plane for a fixed axis; keeps the side with p[axis] >= plane (upper false) or <= plane.
template <int axis, bool upper>
void clip_plane(const Polygon& in, double plane, Polygon& out) {
  std::size_t n = 0;
  Point prev = in.v[in.n - 1];
  double d_prev = upper ? -(prev[axis] - plane) : prev[axis] - plane;
  for (std::size_t i = 0; i < in.n; ++i) {
    const Point cur = in.v[i];
    const double d_cur = upper ? -(cur[axis] - plane) : cur[axis] - plane;
    Point p = prev + (cur - prev) * (d_prev / (d_prev - d_cur));
    p[axis] = plane;
    out.v[n] = p;
    n += (d_prev >= 0.0) != (d_cur >= 0.0);
    out.v[n] = cur;
    n += d_cur >= 0.0;
    prev = cur;
    d_prev = d_cur;
  }
  out.n = std::min(n, kMaxVertices);
}

template <int axis>
void clip_axis(const CutFaces& cut, const Bounds& box, std::array<Polygon, 2>& poly, int& cur) {
  if (poly[cur].n > 0 && cut.lo[axis]) {
    clip_plane<axis, false>(poly[cur], box.lo[axis], poly[1 - cur]);
    cur = 1 - cur;
  }
  if (poly[cur].n > 0 && cut.hi[axis]) {
    clip_plane<axis, true>(poly[cur], box.hi[axis], poly[1 - cur]);
    cur = 1 - cur;
  }
}

const Polygon& clip_to_box(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                           const Bounds& box, const Bounds& extent, std::array<Polygon, 2>& poly) {
  const CutFaces cut = cut_faces(a, b, c, box, extent);
  poly[0].v[0] = point(a);
  poly[0].v[1] = point(b);
  poly[0].v[2] = point(c);
  poly[0].n = 3;
  int cur = 0;
  clip_axis<0>(cut, box, poly, cur);
  clip_axis<1>(cut, box, poly, cur);
  clip_axis<2>(cut, box, poly, cur);
  return poly[cur];
}

// PointBounds with its add taking a point only where `take` is set, in the same order.
struct PointBounds {
  Point lo{kInf, kInf, kInf, kInf};
  Point hi{-kInf, -kInf, -kInf, -kInf};
  Mask any{};

  void add(Point p, Mask take) {
    const Point for_lo = take ? p : Point{kInf, kInf, kInf, kInf};
    const Point for_hi = take ? p : Point{-kInf, -kInf, -kInf, -kInf};
    lo = for_lo < lo ? for_lo : lo;  // glm::min(lo, p): the first of equal values
    hi = hi < for_hi ? for_hi : hi;
    any |= take;
  }
};

// round_down and round_up of three values at once. A float one step towards -inf (+inf) is one
// more (less) in its bits when negative, one less (more) when positive. Zero needs no case of its
// own: only -0 is ever stepped down (to -denorm_min, one more) and only +0 up (to denorm_min).
Float4 round_down(Point x) {
  const Float4 f = __builtin_convertvector(x, Float4);
  const Bits4 bits = reinterpret_cast<Bits4>(f);
  const Mask4 negative = reinterpret_cast<Mask4>(bits) < 0;
  const Bits4 down = negative ? bits + 1u : bits - 1u;
  const Mask4 rounded_up = __builtin_convertvector(__builtin_convertvector(f, Point) > x, Mask4);
  return reinterpret_cast<Float4>(rounded_up ? down : bits);
}

Float4 round_up(Point x) {
  const Float4 f = __builtin_convertvector(x, Float4);
  const Bits4 bits = reinterpret_cast<Bits4>(f);
  const Mask4 negative = reinterpret_cast<Mask4>(bits) < 0;
  const Bits4 up = negative ? bits - 1u : bits + 1u;
  const Mask4 rounded_down = __builtin_convertvector(__builtin_convertvector(f, Point) < x, Mask4);
  return reinterpret_cast<Float4>(rounded_down ? up : bits);
}

Bounds bounds_within(const PointBounds& points, const Bounds& box) {
  if (!points.any[0]) return Bounds{};
  const Float4 box_lo{box.lo.x, box.lo.y, box.lo.z, 0.f};
  const Float4 box_hi{box.hi.x, box.hi.y, box.hi.z, 0.f};
  const Float4 down = round_down(points.lo), up = round_up(points.hi);
  const Float4 lo = box_lo > down ? box_lo : down;  // std::max(down, box_lo)
  const Float4 hi = box_hi < up ? box_hi : up;      // std::min(up, box_hi)
  const Mask4 sliver = lo > hi;
  if (sliver[0] | sliver[1] | sliver[2]) return Bounds{};
  Bounds result;
  result.lo = {lo[0], lo[1], lo[2]};
  result.hi = {hi[0], hi[1], hi[2]};
  return result;
}

template <int axis>
std::array<Bounds, 2> split(const Polygon& inside, const Bounds& cell, float pos) {
  std::array<Bounds, 2> children{cell, cell};
  children[0].hi[axis] = pos;
  children[1].lo[axis] = pos;
  const double plane = pos;
  std::array<PointBounds, 2> side;
  Point prev = inside.v[inside.n - 1];
  double d_prev = prev[axis] - plane;
  for (std::size_t i = 0; i < inside.n; ++i) {
    const Point cur = inside.v[i];
    const double d_cur = cur[axis] - plane;
    Point p = prev + (cur - prev) * (d_prev / (d_prev - d_cur));
    p[axis] = plane;
    side[0].add(p, all((d_prev <= 0.0) != (d_cur <= 0.0)));
    side[0].add(cur, all(d_cur <= 0.0));
    side[1].add(p, all((d_prev >= 0.0) != (d_cur >= 0.0)));
    side[1].add(cur, all(d_cur >= 0.0));
    prev = cur;
    d_prev = d_cur;
  }
  return {bounds_within(side[0], children[0]), bounds_within(side[1], children[1])};
}

}  // namespace

std::array<Bounds, 2> split_triangle_bounds(const glm::vec3& a, const glm::vec3& b,
                                            const glm::vec3& c, const Bounds& cell,
                                            const Bounds& extent, int axis, float pos) {
  std::array<Polygon, 2> poly;
  const Polygon& inside = clip_to_box(a, b, c, cell, extent, poly);
  if (inside.n == 0) return {Bounds{}, Bounds{}};
  switch (axis) {
    case 0: return split<0>(inside, cell, pos);
    case 1: return split<1>(inside, cell, pos);
    default: return split<2>(inside, cell, pos);
  }
}

}  // namespace avx2
#pragma GCC pop_options
#endif

}  // namespace cohort::kd
