// The error bounds of kernels/common/accel/ray_offset.h against the watertight test they guard, on the
// host (the same code the kernels compile): random triangles and slivers, 1e-4 to 1e4 in size and
// up to 1e5 from the origin, hit from random eyes; rays leaving the offset hit point (grazing ones
// included) never hit their own triangle or its neighbour across a shared edge, and shadow rays
// stopped by shadow_tmax never reach the light's own triangle. The sweep behind the constant
// (docs/design.md) found the first failures at 1 epsilon; the constant is 16. Slivers thinner than
// RAY_OFFSET_MAX_ASPECT are left out: their offset is capped, so they may self-intersect.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/common/accel/intersect.h"
#include "kernels/common/accel/ray_offset.h"
#include "kernels/common/core/sampling.h"

namespace {

struct Sweep {
  std::mt19937 rng{1};
  std::uniform_real_distribution<float> unit{0.f, 1.f};
  float u() { return unit(rng); }
  co_vec3 in_cube() { return v3(2 * u() - 1, 2 * u() - 1, 2 * u() - 1); }
  float log_uniform(float lo_exp, float hi_exp) { return std::pow(10.f, lo_exp + (hi_exp - lo_exp) * u()); }
};

struct Quad {
  co_vec3 p0, p1, p2, p3;  // triangles (p0, p1, p2) and (p1, p3, p2) share the edge p1 p2
  co_vec3 cross, n;
  float size;
};

Quad any_quad(Sweep& s) {
  const float size = s.log_uniform(-4, 4);
  const co_vec3 centre = v3_scale(s.in_cube(), s.u() < 0.3f ? 0.f : s.log_uniform(-5, 5));
  const co_vec3 e1 = v3_scale(s.in_cube(), size);
  co_vec3 e2 = v3_scale(s.in_cube(), size);
  if (s.u() < 0.3f) e2 = v3_madd(v3_scale(e1, s.u()), s.in_cube(), size * 1e-3f);  // a sliver
  Quad q;
  q.p0 = centre;
  q.p1 = v3_add(centre, e1);
  q.p2 = v3_add(centre, e2);
  q.p3 = v3_add(q.p1, v3_sub(q.p2, q.p0));
  q.cross = v3_cross(v3_sub(q.p1, q.p0), v3_sub(q.p2, q.p0));
  q.n = v3_normalize(q.cross);
  q.size = size;
  return q;
}

// Longest edge squared over |cross|: the aspect ratio that RAY_OFFSET_MAX_ASPECT caps.
float aspect(const Quad& q) {
  const co_vec3 e0 = v3_sub(q.p1, q.p0), e1 = v3_sub(q.p2, q.p0), e2 = v3_sub(q.p2, q.p1);
  return std::fmax(v3_dot(e0, e0), std::fmax(v3_dot(e1, e1), v3_dot(e2, e2))) / v3_length(q.cross);
}

// A random quad within the aspect ratio the bound covers.
Quad random_quad(Sweep& s) {
  for (;;) {
    const Quad q = any_quad(s);
    if (aspect(q) <= RAY_OFFSET_MAX_ASPECT) return q;
  }
}

// A point of the triangle hit from a random eye, as path_shade rebuilds it.
bool hit_from_eye(Sweep& s, const Quad& q, co_vec3* pos, float* offset) {
  float a = s.u(), b = s.u();
  if (a + b > 1) a = 1 - a, b = 1 - b;
  const co_vec3 target = v3_add(q.p0, v3_add(v3_scale(v3_sub(q.p1, q.p0), a), v3_scale(v3_sub(q.p2, q.p0), b)));
  const co_vec3 eye = v3_add(target, v3_scale(s.in_cube(), q.size * s.log_uniform(-2, 4)));
  const WatertightRay r = watertight_ray(eye, v3_normalize(v3_sub(target, eye)));
  float t, hu, hv, magnitude;
  if (!intersect_triangle(&r, q.p0, q.p1, q.p2, 0.f, INFINITY, &t, &hu, &hv)) return false;
  *pos = triangle_point(q.p0, q.p1, q.p2, hu, hv, &magnitude);
  *offset = surface_offset(magnitude, triangle_edge_error(q.p0, q.p1, q.p2, q.cross));
  return true;
}

TEST(RayOffsetBound, RaysLeavingASurfaceNeverHitItOrItsNeighbour) {
  Sweep s;
  long rays = 0, self_hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Quad q = random_quad(s);
    for (int k = 0; k < 20; ++k) {
      co_vec3 pos;
      float offset;
      if (!hit_from_eye(s, q, &pos, &offset)) continue;
      for (int j = 0; j < 20; ++j) {
        co_vec3 w = v3_normalize(s.in_cube());
        // a quarter of them within 1e-4 of the tangent plane
        if (j < 5) w = v3_normalize(v3_madd(w, q.n, -v3_dot(w, q.n) * (1 - 1e-4f * s.u())));
        const float cos_n = v3_dot(w, q.n);
        if (cos_n == 0.f) continue;
        const WatertightRay r = watertight_ray(offset_origin(pos, q.n, offset, cos_n > 0.f), w);
        float t, hu, hv;
        ++rays;
        self_hits += intersect_triangle(&r, q.p0, q.p1, q.p2, 0.f, INFINITY, &t, &hu, &hv) ||
                     intersect_triangle(&r, q.p1, q.p3, q.p2, 0.f, INFINITY, &t, &hu, &hv);
      }
    }
  }
  EXPECT_GT(rays, 500000);
  EXPECT_EQ(self_hits, 0) << "of " << rays << " rays";
}

TEST(RayOffsetBound, ShadowRaysStopShortOfTheLight) {
  Sweep s;
  long rays = 0, light_hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Quad q = random_quad(s);
    const float edge_error = triangle_edge_error(q.p0, q.p1, q.p2, q.cross);
    for (int k = 0; k < 200; ++k) {
      float b1, b2, magnitude;
      sample_triangle(s.u(), s.u(), &b1, &b2);
      const co_vec3 pl = triangle_point(q.p0, q.p1, q.p2, b1, b2, &magnitude);
      const co_vec3 org = v3_add(pl, v3_scale(s.in_cube(), s.log_uniform(-6, 6) * std::fmax(q.size, v3_max_abs(q.p0))));
      const co_vec3 d = v3_sub(pl, org);
      const float dist = v3_length(d);
      const co_vec3 w = v3_scale(d, 1.f / dist);
      const float tmax = shadow_tmax(dist, std::fmax(magnitude, v3_max_abs(org)), edge_error, std::fabs(v3_dot(w, q.n)));
      if (!(tmax > 0.f)) continue;
      const WatertightRay r = watertight_ray(org, w);
      float t, hu, hv;
      ++rays;
      light_hits += intersect_triangle(&r, q.p0, q.p1, q.p2, 0.f, tmax, &t, &hu, &hv);
    }
  }
  EXPECT_GT(rays, 300000);
  EXPECT_EQ(light_hits, 0) << "of " << rays << " rays";
}

}  // namespace
