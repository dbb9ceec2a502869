/* Where a new ray may start off a surface, and where a shadow ray must stop short of a light, from
 * bounds on floating-point error instead of the scene's size (pbrt-v4 section 6.8; Wachter and
 * Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6).
 *
 * A hit point is rebuilt from its barycentrics, so it lies on the triangle to within a few ulps of
 * the magnitude of the vertices that weigh in it, |b0 p0| + |b1 p1| + |b2 p2|, however long the ray
 * was. The watertight test (intersect.h) then errs in t by a few ulps of that magnitude plus, from
 * its edge functions, of L^3 / |e1 x e2| (L the longest edge: 2L for a well-shaped triangle, more
 * for a sliver). Offsets are RAY_OFFSET_EPSILONS float epsilons of their sum: a brute-force sweep
 * (random triangles and slivers, 1e-4 to 1e4 in size, up to 1e5 from the origin, grazing rays)
 * found no self-hit above 2 epsilons, so 16 leaves a factor 8. Every quantity scales with the
 * coordinates, so a scene scaled by a power of two renders the same image bit for bit. */
#ifndef COHORT_RAY_OFFSET_H
#define COHORT_RAY_OFFSET_H

#include "common/core/vec.h"

#define RAY_OFFSET_EPSILONS 16.0f
#define RAY_OFFSET_SCALE (RAY_OFFSET_EPSILONS * 0x1p-23f)
/* a sliver's edge term is capped at this many times its longest edge (an aspect ratio of 4096):
 * a degenerate triangle must not throw the next ray across the scene */
#define RAY_OFFSET_MAX_ASPECT 4096.0f

CO_INLINE float v3_max_abs(co_vec3 a) { return v3_max_component(v3_abs(a)); }

/* The point at barycentrics (b1, b2) (the weights of p1 and p2), and in *magnitude the size its
 * rounding error scales with. */
CO_INLINE co_vec3 triangle_point(co_vec3 p0, co_vec3 p1, co_vec3 p2, float b1, float b2, float* magnitude) {
  co_vec3 a = v3_scale(p0, 1.0f - b1 - b2), b = v3_scale(p1, b1), c = v3_scale(p2, b2);
  *magnitude = v3_max_component(v3_add(v3_add(v3_abs(a), v3_abs(b)), v3_abs(c)));
  return v3_add(v3_add(a, b), c);
}

/* L^3 / |cross| (cross = (p1 - p0) x (p2 - p0)): L times the aspect ratio L^2 / |cross|, capped
 * at RAY_OFFSET_MAX_ASPECT; how much the watertight test's edge functions magnify rounding on this
 * triangle, as a length. */
CO_INLINE float triangle_edge_error(co_vec3 p0, co_vec3 p1, co_vec3 p2, co_vec3 cross) {
  co_vec3 e0 = v3_sub(p1, p0), e1 = v3_sub(p2, p0), e2 = v3_sub(p2, p1);
  float l = sqrt(fmax(v3_dot(e0, e0), fmax(v3_dot(e1, e1), v3_dot(e2, e2))));
  return l * fmin(l * l / v3_length(cross), RAY_OFFSET_MAX_ASPECT);
}

/* How far off the surface a ray from this hit point starts; never 0, so even a triangle through
 * the origin moves its rays off its plane. */
CO_INLINE float surface_offset(float magnitude, float edge_error) {
  return fmax(RAY_OFFSET_SCALE * (magnitude + edge_error), 0x1p-126f);
}

/* `p` moved `offset` along the unit normal n, to the front when `front`, else to the back. */
CO_INLINE co_vec3 offset_origin(co_vec3 p, co_vec3 n, float offset, int front) {
  return v3_madd(p, n, front ? offset : -offset);
}

/* The tmax of a shadow ray towards a point `dist` away on a light, as computed from the ray's
 * origin: short of the light by the error with which the watertight test finds the light's own
 * surface (`magnitude` is the larger of the origin's and the light point's, `edge_error` the
 * light triangle's, cos_light the cosine at the light; 0 and 1 for a punctual light): the light's
 * own triangle never occludes it, anything farther from it than that bound does. Not positive
 * when the light is too close to tell. */
CO_INLINE float shadow_tmax(float dist, float magnitude, float edge_error, float cos_light) {
  return dist - RAY_OFFSET_SCALE * (magnitude + dist + edge_error) / cos_light;
}

#endif
