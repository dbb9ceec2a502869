/* A 3-vector as a plain struct with named functions, so the same code compiles as OpenCL C
 * (no overloading, no operators) and as C++. Compilers keep it in registers. */
#ifndef COHORT_VEC_H
#define COHORT_VEC_H

#include "common/core/port.h"

typedef struct co_vec3 {
  float x, y, z;
} co_vec3;

CO_INLINE co_vec3 v3(float x, float y, float z) { co_vec3 r; r.x = x; r.y = y; r.z = z; return r; }
CO_INLINE co_vec3 v3_splat(float s) { return v3(s, s, s); }
CO_INLINE co_vec3 v3_from4(co_float4 a) { return v3(a.x, a.y, a.z); }
CO_INLINE co_vec3 v3_add(co_vec3 a, co_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
CO_INLINE co_vec3 v3_sub(co_vec3 a, co_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
CO_INLINE co_vec3 v3_mul(co_vec3 a, co_vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
CO_INLINE co_vec3 v3_scale(co_vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
/* a + b * s, written out so every kernel rounds it the same way (no contraction is enabled). */
CO_INLINE co_vec3 v3_madd(co_vec3 a, co_vec3 b, float s) { return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
CO_INLINE co_vec3 v3_neg(co_vec3 a) { return v3(-a.x, -a.y, -a.z); }
CO_INLINE float v3_dot(co_vec3 a, co_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
CO_INLINE co_vec3 v3_cross(co_vec3 a, co_vec3 b) {
  return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
CO_INLINE float v3_length(co_vec3 a) { return sqrt(v3_dot(a, a)); }
CO_INLINE co_vec3 v3_normalize(co_vec3 a) { return v3_scale(a, 1.0f / v3_length(a)); }
CO_INLINE float v3_max_component(co_vec3 a) { return fmax(a.x, fmax(a.y, a.z)); }
CO_INLINE float v3_get(co_vec3 a, uint32_t axis) { return axis == 0 ? a.x : (axis == 1 ? a.y : a.z); }
CO_INLINE co_vec3 v3_abs(co_vec3 a) { return v3(fabs(a.x), fabs(a.y), fabs(a.z)); }
CO_INLINE int v3_is_finite(co_vec3 a) {
  /* written without isfinite() so that it survives any math flags */
  float s = a.x + a.y + a.z;
  return s == s && s - s == 0.0f;
}

#endif
