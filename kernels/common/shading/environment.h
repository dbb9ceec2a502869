/* The environment map (`--env FILE.exr`, docs/lights.md): an equirectangular image in Mitsuba 3's
 * `envmap` convention, looked up bilinearly, and sampled for next-event estimation from a
 * piecewise-constant distribution over the cells of the bilinear grid.
 *
 * Convention (Mitsuba's, so its renders compare exactly): +y is up; a world direction d has
 * u = atan2(d.x, -d.z) / 2pi, v = acos(d.y) / pi; the image's first row is the +y pole (v = 0) and
 * its last row the -y pole (v = 1), so rows lie at theta_j = j pi / (H - 1); column i sits at
 * u = (i + 1/2) / W. The texels form a (W + 1) x H grid whose last column repeats the first, and
 * the radiance between grid points is bilinear in (u, theta).
 *
 * Sampling: a cell is the patch between grid columns i, i + 1 and rows j, j + 1 (W x (H - 1)
 * cells). Its weight is the mean luminance of its four corners times its solid angle, so the
 * pdf is positive wherever the bilinear radiance is. A row is picked from the marginal cdf, a
 * column from that row's conditional cdf, and the point inside the cell uniformly in solid angle
 * (uniform in u and in cos theta), so the solid-angle pdf is constant over a cell: its
 * probability over its solid angle, with no 1/sin(theta) at the poles. */
#ifndef COHORT_ENVIRONMENT_H
#define COHORT_ENVIRONMENT_H

#include "common/shading/microfacet.h"
#include "common/core/sampling.h"

typedef struct EnvironmentView {
  const CO_GLOBAL co_float4* texels; /* (width + 1) x height, rgb */
  const CO_GLOBAL float* tables;     /* cos theta per row [height], marginal cdf [height - 1],
                                        conditional cdfs [(height - 1) x width] */
  uint32_t width, height;            /* of the image; height 0: none */
} EnvironmentView;

CO_INLINE const CO_GLOBAL float* env_cos_theta(const EnvironmentView* e) { return e->tables; }
CO_INLINE const CO_GLOBAL float* env_marginal(const EnvironmentView* e) { return e->tables + e->height; }
CO_INLINE const CO_GLOBAL float* env_conditional(const EnvironmentView* e, uint32_t row) {
  return e->tables + e->height + (e->height - 1u) + row * e->width;
}

/* atan2(y, x) from adds, multiplies, divides, square roots and compares only, all correctly
 * rounded, so every device and the host get the same bits (OpenCL allows the built-in atan2 and
 * acos 6 and 4 ulp, and PoCL and Intel's runtime differ: docs/vendors.md). The ratio t in [0, 1] is
 * halved in angle twice (atan t = 2 atan(t / (1 + sqrt(1 + t^2)))) to at most tan(pi/16) ~ 0.2,
 * where the Taylor series to x^15 is accurate to float precision; octant symmetries restore the
 * angle. */
CO_INLINE float co_atan2(float y, float x) {
  float ax = fabs(x), ay = fabs(y);
  float hi = fmax(ax, ay), lo = fmin(ax, ay);
  if (hi == 0.0f) return 0.0f;
  float t = lo / hi;
  t = t / (1.0f + sqrt(1.0f + t * t));
  t = t / (1.0f + sqrt(1.0f + t * t));
  float t2 = t * t;
  float a = t * (1.0f + t2 * (-1.0f / 3.0f + t2 * (1.0f / 5.0f + t2 * (-1.0f / 7.0f + t2 * (1.0f / 9.0f +
                 t2 * (-1.0f / 11.0f + t2 * (1.0f / 13.0f + t2 * (-1.0f / 15.0f))))))));
  a = 4.0f * a;
  if (ay > ax) a = 0.5f * CO_PI - a;
  if (x < 0.0f) a = CO_PI - a;
  return y < 0.0f ? -a : a;
}

/* acos(c) for c in [-1, 1], through co_atan2 (see there). */
CO_INLINE float co_acos(float c) { return co_atan2(sqrt((1.0f - c) * (1.0f + c)), c); }

/* Grid coordinates of a unit direction: cell (*i, *j) and the bilinear weights (*fx, *fy) in it. */
CO_INLINE void env_cell(const EnvironmentView* e, co_vec3 d, uint32_t* i, uint32_t* j, float* fx, float* fy) {
  float u = co_atan2(d.x, -d.z) * (0.5f * CO_INV_PI);
  float v = co_acos(fmin(fmax(d.y, -1.0f), 1.0f)) * CO_INV_PI;
  u -= 0.5f / (float)e->width; /* column centres at (i + 1/2) / W */
  u -= floor(u);
  u *= (float)e->width;
  v *= (float)(e->height - 1u);
  uint32_t x = (uint32_t)u, y = (uint32_t)v;
  x = x < e->width - 1u ? x : e->width - 1u;
  y = y < e->height - 2u ? y : e->height - 2u;
  *i = x;
  *j = y;
  *fx = u - (float)x;
  *fy = v - (float)y;
}

/* Radiance arriving from direction d (unit, pointing away from the scene). */
CO_INLINE co_vec3 env_eval(const EnvironmentView* e, co_vec3 d) {
  uint32_t i, j;
  float fx, fy;
  env_cell(e, d, &i, &j, &fx, &fy);
  uint32_t row = e->width + 1u, k = j * row + i;
  co_vec3 a = v3_from4(e->texels[k]), b = v3_from4(e->texels[k + 1u]);
  co_vec3 c = v3_from4(e->texels[k + row]), g = v3_from4(e->texels[k + row + 1u]);
  co_vec3 top = v3_add(v3_scale(a, 1.0f - fx), v3_scale(b, fx));
  co_vec3 bottom = v3_add(v3_scale(c, 1.0f - fx), v3_scale(g, fx));
  return v3_add(v3_scale(top, 1.0f - fy), v3_scale(bottom, fy));
}

/* Probability of cell (i, j) over its solid angle. */
CO_INLINE float env_cell_pdf(const EnvironmentView* e, uint32_t i, uint32_t j) {
  const CO_GLOBAL float* marginal = env_marginal(e);
  const CO_GLOBAL float* cond = env_conditional(e, j);
  float p_row = marginal[j] - (j > 0u ? marginal[j - 1u] : 0.0f);
  float p_col = cond[i] - (i > 0u ? cond[i - 1u] : 0.0f);
  const CO_GLOBAL float* cos_theta = env_cos_theta(e);
  float solid_angle = (2.0f * CO_PI / (float)e->width) * (cos_theta[j] - cos_theta[j + 1u]);
  return p_row * p_col / solid_angle;
}

/* Solid-angle density with which env_sample returns direction d. */
CO_INLINE float env_pdf(const EnvironmentView* e, co_vec3 d) {
  uint32_t i, j;
  float fx, fy;
  env_cell(e, d, &i, &j, &fx, &fy);
  return env_cell_pdf(e, i, j);
}

/* First index of cdf[0..n) whose value exceeds u, and u's position inside that step, in [0, 1). */
CO_INLINE uint32_t env_search(const CO_GLOBAL float* cdf, uint32_t n, float u, float* frac) {
  uint32_t lo = 0u, hi = n - 1u;
  while (lo < hi) {
    uint32_t mid = (lo + hi) >> 1;
    if (u < cdf[mid]) hi = mid; else lo = mid + 1u;
  }
  float below = lo > 0u ? cdf[lo - 1u] : 0.0f;
  float step = cdf[lo] - below;
  float f = step > 0.0f ? (u - below) / step : 0.5f;
  *frac = fmin(fmax(f, 0.0f), 0x1.fffffep-1f);
  return lo;
}

/* A direction (unit, away from the scene) from (u1, u2) in [0, 1); *pdf is its solid-angle density. */
CO_INLINE co_vec3 env_sample(const EnvironmentView* e, float u1, float u2, float* pdf) {
  float fv, fu;
  uint32_t j = env_search(env_marginal(e), e->height - 1u, u1, &fv);
  uint32_t i = env_search(env_conditional(e, j), e->width, u2, &fu);
  *pdf = env_cell_pdf(e, i, j);
  const CO_GLOBAL float* cos_theta = env_cos_theta(e);
  float cos_t = cos_theta[j] + (cos_theta[j + 1u] - cos_theta[j]) * fv;
  float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t));
  float u = ((float)i + 0.5f + fu) / (float)e->width;
  if (u >= 1.0f) u -= 1.0f;
  float sin_phi, cos_phi;
  co_sincos_2pi(u, &sin_phi, &cos_phi);
  return v3(sin_phi * sin_t, cos_t, -cos_phi * sin_t);
}

#endif
