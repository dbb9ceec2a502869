/* Sampling routines and the local frame they work in. */
#ifndef COHORT_SAMPLING_H
#define COHORT_SAMPLING_H

#include "common/core/vec.h"

#define CO_PI 3.14159265358979323846f
#define CO_INV_PI 0.31830988618379067154f

/* Orthonormal basis around a unit normal (Duff et al., "Building an Orthonormal Basis, Revisited",
 * JCGT 2017): branch-free and without the singularity of the cross-product method. */
CO_INLINE void onb_from_normal(co_vec3 n, co_vec3* t, co_vec3* b) {
  float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  *t = v3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = v3(c, sign + n.y * n.y * a, -n.y);
}

/* Cosine-weighted direction about n; pdf = cos(theta) / pi. */
CO_INLINE co_vec3 sample_cosine_hemisphere(co_vec3 n, float u1, float u2) {
  float r = sqrt(u1);
  float phi = 2.0f * CO_PI * u2;
  float lx = r * cos(phi), ly = r * sin(phi), lz = sqrt(fmax(0.0f, 1.0f - u1));
  co_vec3 t, b;
  onb_from_normal(n, &t, &b);
  return v3_add(v3_add(v3_scale(t, lx), v3_scale(b, ly)), v3_scale(n, lz));
}

/* Uniform point on a triangle as barycentric weights of (v1, v2). */
CO_INLINE void sample_triangle(float u1, float u2, float* b1, float* b2) {
  float su = sqrt(u1);
  *b1 = su * (1.0f - u2);
  *b2 = su * u2;
}

/* Power heuristic with beta = 2 (Veach 1997). */
CO_INLINE float mis_power(float pdf_a, float pdf_b) {
  float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a / (a + b);
}

#endif
