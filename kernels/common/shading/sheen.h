/* glTF KHR_materials_sheen: the sheen lobe and what the layering needs (docs/bsdf.md, "Sheen"). Plain C
 * for OpenCL C 1.2, CUDA and host C++; compiled into rendering programs only with COHORT_FEATURE_SHEEN.
 *
 *   f_sheen(wi, wo) = sheenColor D(h) V(wi, wo)
 *   D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi)                     (Charlie; Estevez & Kulla 2017)
 *   V    = 1 / ((1 + Lambda(cos_i) + Lambda(cos_o)) 4 cos_i cos_o)           (their fitted Lambda, as glTF gives it)
 *   alpha = max(sheenRoughness^2, SHEEN_ALPHA_MIN)
 *   material = f_sheen + base (1 - max3(sheenColor) E(cos_i, alpha))        (glTF's albedo scaling, view only)
 * with E the lobe's directional albedo, a table integrated once (sheen_albedo.h, written by
 * scripts/lib/sheen-albedo.py). Every function the kernels call rounds identically on the host and on
 * every device: the powers and exponentials go through co_log and co_exp (+, -, *, floor and bit
 * operations), never the built-in pow/log/exp. */
#ifndef COHORT_SHEEN_H
#define COHORT_SHEEN_H

#include "common/core/types.h"
#include "common/core/vec.h"
#include "common/shading/bsdf.h"
#include "common/shading/medium.h"
#include "common/shading/sheen_albedo.h"

/* alpha below this counts as this: float resolves sin^(1/alpha) here (sin^2 = 1 - cos^2 has an error
 * near 6e-8, raised to 0.5/alpha), and the same bound as BSDF_SMOOTH_ALPHA (glTF roughness 0.032). */
#define SHEEN_ALPHA_MIN 1e-3f

/* Natural logarithm from +, -, *, and bit operations, so that the host and every device round it alike
 * (co_exp's companion, medium.h). x = 2^k m with m in [sqrt(1/2), sqrt(2)); log(m) = f P(f), f = m - 1
 * (exact), P the Chebyshev interpolant of log1p(f)/f of degree 10 (scripts/lib/sheen-albedo.py
 * --log-coefficients), within about 2 ulp; k ln 2 uses fdlibm's split of ln 2. 0, subnormals and
 * negative numbers give -infinity (subnormals: so that flushing them cannot differ between devices),
 * infinity stays infinity, NaN stays NaN. */
CO_INLINE float co_log(float x) {
  if (x != x) return x;
  if (!(x >= 0x1p-126f)) return -INFINITY;
  if (x > 0x1.fffffep+127f) return x;
  uint32_t bits = co_as_uint(x);
  int32_t k = (int32_t)(bits >> 23) - 127;
  float m = co_as_float((bits & 0x007fffffu) | 0x3f800000u); /* [1, 2) */
  if (m > 0x1.6a09e6p+0f) {                                    /* sqrt(2) */
    m = m * 0.5f;
    k = k + 1;
  }
  float f = m - 1.0f;
  float p = 0x1.1414760p-4f;
  p = p * f + -0x1.e058e80p-4f;
  p = p * f + 0x1.e8676e0p-4f;
  p = p * f + -0x1.fbdf420p-4f;
  p = p * f + 0x1.2312fe0p-3f;
  p = p * f + -0x1.555c8c0p-3f;
  p = p * f + 0x1.99a71c0p-3f;
  p = p * f + -0x1.0000100p-2f;
  p = p * f + 0x1.5555400p-2f;
  p = p * f + -0.5f;
  p = p * f + 1.0f;
  float kf = (float)k;
  return kf * 0x1.62e300p-1f + (f * p + kf * 0x1.2fefa2p-17f);
}

/* x^y for x >= 0 through co_log and co_exp (0 for x = 0 and y > 0). */
CO_INLINE float co_pow(float x, float y) { return co_exp(y * co_log(x)); }

CO_INLINE float sheen_alpha(float roughness) {
  float r = fmin(fmax(roughness, 0.0f), 1.0f);
  return fmax(r * r, SHEEN_ALPHA_MIN);
}

/* Charlie distribution of the unit half vector h (upper hemisphere); sin^2 theta_h from x and y. */
CO_INLINE float sheen_d(co_vec3 h, float alpha) {
  float inv_alpha = 1.0f / alpha;
  float sin2 = h.x * h.x + h.y * h.y;
  return (2.0f + inv_alpha) * co_exp(0.5f * inv_alpha * co_log(sin2)) * (0.5f * CO_INV_PI);
}

/* Estevez & Kulla's fitted L(x), its five coefficients interpolated in (1 - alpha)^2 as glTF's
 * specification does; Lambda(cos) = exp(L(cos)) below 0.5, exp(2 L(0.5) - L(1 - cos)) above. */
CO_INLINE float sheen_l(float x, float alpha) {
  float t = (1.0f - alpha) * (1.0f - alpha);
  float a = 21.5473f + (25.3245f - 21.5473f) * t;
  float b = 3.82987f + (3.32435f - 3.82987f) * t;
  float c = 0.19823f + (0.16801f - 0.19823f) * t;
  float d = -1.97760f + (-1.27393f + 1.97760f) * t;
  float e = -4.32054f + (-4.85967f + 4.32054f) * t;
  return a / (1.0f + b * co_pow(x, c)) + d * x + e;
}
CO_INLINE float sheen_lambda(float cos_theta, float alpha) {
  if (cos_theta < 0.5f) return co_exp(sheen_l(cos_theta, alpha));
  return co_exp(2.0f * sheen_l(0.5f, alpha) - sheen_l(1.0f - cos_theta, alpha));
}

/* f_sheen cos theta_o for sheen colour 1, both directions above the surface (0 otherwise). */
CO_INLINE float sheen_lobe(co_vec3 wi, co_vec3 wo, float alpha) {
  if (!(wi.z > 0.0f) || !(wo.z > 0.0f)) return 0.0f;
  co_vec3 h = v3_add(wi, wo);
  float len = v3_length(h);
  if (!(len > 0.0f)) return 0.0f;
  h = v3_scale(h, 1.0f / len);
  float g = 1.0f + sheen_lambda(wi.z, alpha) + sheen_lambda(wo.z, alpha);
  return sheen_d(h, alpha) / (g * 4.0f * wi.z);
}

/* E(cos_i, roughness): the table bilinearly, at sqrt(cos_i) and the roughness clamped to [0, 1]. */
CO_INLINE float sheen_albedo(float cos_i, float roughness) {
  float x = sqrt(fmin(fmax(cos_i, 0.0f), 1.0f)) * (float)(SHEEN_ALBEDO_N - 1u);
  float y = fmin(fmax(roughness, 0.0f), 1.0f) * (float)(SHEEN_ALBEDO_N - 1u);
  float fx = fmin(floor(x), (float)(SHEEN_ALBEDO_N - 2u)), fy = fmin(floor(y), (float)(SHEEN_ALBEDO_N - 2u));
  float tx = x - fx, ty = y - fy;
  uint32_t i = (uint32_t)fx * SHEEN_ALBEDO_N + (uint32_t)fy;
  float e0 = co_sheen_albedo[i] * (1.0f - ty) + co_sheen_albedo[i + 1u] * ty;
  float e1 = co_sheen_albedo[i + SHEEN_ALBEDO_N] * (1.0f - ty) + co_sheen_albedo[i + SHEEN_ALBEDO_N + 1u] * ty;
  return e0 * (1.0f - tx) + e1 * tx;
}

/* The probability with which a shading point takes the sheen lobe: max3(sheenColor) E(|cos_i|), at
 * most 1 (E exceeds 1 at grazing views for sheenRoughness below about 0.25 under this Lambda fit; the
 * base then gets no share, max(0, 1 - max3 E)). */
CO_INLINE float sheen_probability(co_vec3 color, float roughness, float cos_i) {
  float q = v3_max_component(color) * sheen_albedo(fabs(cos_i), roughness);
  return fmin(q, 1.0f);
}

/* ---- Sheen (KHR_materials_sheen, sheen.h) ----------------------------------------------------------
 * The sheen lobe alone: eval = color D V cos_o (color: the sheen colour over the probability with
 * which bsdf_sheen_select took the lobe), sampled cosine-weighted, the lobe being broad: pdf = cos_o /
 * pi, weight = color D V pi. alpha = max(sheenRoughness^2, SHEEN_ALPHA_MIN); two-sided. */
CO_INLINE Bsdf bsdf_sheen(co_vec3 color, float roughness) {
  Bsdf b;
  b.type = BSDF_SHEEN;
  b.alpha = sheen_alpha(roughness);
  b.eta = 1.0f;
  b.spec_weight = 0.0f;
  b.color = color;
  b.fdr_int = 0.0f;
  return b;
}
CO_INLINE co_vec3 sheen_eval(const Bsdf* b, co_vec3 wi, co_vec3 wo) {
  return v3_scale(b->color, sheen_lobe(wi, wo, b->alpha));
}
/* Sampled as the Lambertian is (its direction and pdf, as bsdf_pdf's diffuse_pdf), weighted by the lobe. */
CO_INLINE BsdfSample sheen_sample(const Bsdf* b, co_vec3 wi, float u1, float u2) {
  BsdfSample s = diffuse_sample(b, wi, u1, u2);
  if (s.flags == 0u) return s;
  s.weight = v3_scale(sheen_eval(b, wi, s.wo), 1.0f / s.pdf);
  s.flags = BSDF_REFLECTION | BSDF_GLOSSY;
  return s;
}

/* glTF puts the sheen above the base: material = f_sheen + base (1 - max3(sheenColor) E(cos_i)). The
 * sheen lobe is taken with probability q = max3(sheenColor) E(|cos_i|) (at most 1, sheen_probability),
 * its colour divided by q; otherwise *u_select is remapped to [0, 1) given "not sheen" for the base's
 * own choice (bsdf_from_gltf), whose weight (1 - max3 E) / (1 - q) is then exactly 1. Returns 1 when
 * the sheen lobe is taken (*b set). wi: the local incoming direction, as bsdf_eval takes it. */
CO_INLINE int bsdf_sheen_select(co_vec3 sheen_color, float sheen_roughness, co_vec3 wi, float* u_select, Bsdf* b) {
  co_vec3 color = v3(fmin(fmax(sheen_color.x, 0.0f), 1.0f), fmin(fmax(sheen_color.y, 0.0f), 1.0f),
                     fmin(fmax(sheen_color.z, 0.0f), 1.0f));
  if (!(v3_max_component(color) > 0.0f)) return 0; /* no sheen: u_select stays as it is */
  float q = sheen_probability(color, sheen_roughness, wi.z);
  if (*u_select < q) {
    *b = bsdf_sheen(v3_scale(color, 1.0f / q), sheen_roughness);
    return 1;
  }
  if (q > 0.0f) *u_select = fmin((*u_select - q) / (1.0f - q), 0x1.fffffep-1f);
  return 0;
}

#endif
