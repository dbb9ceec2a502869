/* Fresnel terms and the GGX (Trowbridge-Reitz) microfacet distribution, in the local shading frame
 * (z = shading normal). Plain C for OpenCL C 1.2 and host C++; see docs/bsdf.md.
 *
 * References
 *   Walter, Marschner, Li, Torrance, "Microfacet Models for Refraction through Rough Surfaces",
 *     EGSR 2007 (GGX, transmission Jacobian).
 *   Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 2014
 *     (Smith Lambda, height-correlated G2).
 *   Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 2018 (VNDF sampling).
 *   Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", CGF 1994. */
#ifndef COHORT_MICROFACET_H
#define COHORT_MICROFACET_H

#include "common/core/sampling.h"

/* cos and sin of 2 pi u for u in [0, 1], from adds, multiplies and compares only, so the host and
 * every OpenCL device round them identically (the built-in cos/sin may differ by up to 4 ulp, which
 * sampling then amplifies near grazing angles). u * 4 is exact, so the quadrant and the remainder
 * r in [-1/2, 1/2) are exact; x = r pi/2 lies in [-pi/4, pi/4], where the Taylor polynomials below
 * (to x^11 and x^12) are accurate to about 1 ulp. */
#define CO_SIN_POLY(x, x2)                                                                         \
  ((x) * (1.0f + (x2) * (-1.0f / 6.0f + (x2) * (1.0f / 120.0f + (x2) * (-1.0f / 5040.0f +                \
                 (x2) * (1.0f / 362880.0f + (x2) * (-1.0f / 39916800.0f)))))))
#define CO_COS_POLY(x2)                                                                            \
  (1.0f + (x2) * (-0.5f + (x2) * (1.0f / 24.0f + (x2) * (-1.0f / 720.0f + (x2) * (1.0f / 40320.0f +       \
                 (x2) * (-1.0f / 3628800.0f + (x2) * (1.0f / 479001600.0f)))))))
/* (the polynomials are macros so that the eight-lane form, shade_batch.h, rounds as this one does) */
CO_INLINE void co_sincos_2pi(float u, float* s, float* c) {
  float q4 = u * 4.0f;
  int k = (int)q4;
  float r = q4 - (float)k;
  if (r >= 0.5f) {
    r -= 1.0f;
    k += 1;
  }
  float x = r * (0.5f * CO_PI);
  float x2 = x * x;
  float sx = CO_SIN_POLY(x, x2), cx = CO_COS_POLY(x2);
  /* the quadrant by selects rather than branches: k is as random as u, so a branch on it missed
   * about every other time (quadrants 0-3: sin sx, cx, -sx, -cx; cos cx, -sx, -cx, sx) */
  float sin_r = (k & 1) ? cx : sx, cos_r = (k & 1) ? sx : cx;
  *s = (k & 2) ? -sin_r : sin_r;
  *c = ((k + 1) & 2) ? -cos_r : cos_r;
}

CO_INLINE float co_safe_sqrt(float x) { return sqrt(fmax(x, 0.0f)); }

/* Mirror of v about the unit vector m (both pointing away from the surface). */
CO_INLINE co_vec3 v3_reflect(co_vec3 v, co_vec3 m) {
  float d = 2.0f * v3_dot(v, m);
  return v3(m.x * d - v.x, m.y * d - v.y, m.z * d - v.z);
}

/* ---- Fresnel ------------------------------------------------------------------------------- */

/* Exact unpolarised Fresnel reflectance of a smooth dielectric interface (as Mitsuba 3's
 * fresnel()). eta = interior IOR / exterior IOR; cos_i > 0 means the incident direction lies on the
 * exterior side (the normal's side). Outputs: *cos_t = cosine of the refracted direction, signed
 * (on the other side of the interface from cos_i; 0 under total internal reflection, where the
 * result is 1), and *eta_ti = IOR of the incident side over IOR of the transmitted side. */
CO_INLINE float fresnel_dielectric(float cos_i, float eta, float* cos_t, float* eta_ti) {
  int outside = cos_i >= 0.0f;
  float eta_it = outside ? eta : 1.0f / eta;
  float e_ti = outside ? 1.0f / eta : eta;
  float cos_t_sqr = 1.0f - (1.0f - cos_i * cos_i) * (e_ti * e_ti);
  float ci = fabs(cos_i);
  float ct = co_safe_sqrt(cos_t_sqr);
  float r;
  if (eta == 1.0f) {
    r = 0.0f; /* index-matched: the interface is invisible */
  } else if (ci == 0.0f) {
    r = 1.0f;
  } else {
    float a_s = (ci - eta_it * ct) / (ci + eta_it * ct);
    float a_p = (ct - eta_it * ci) / (ct + eta_it * ci);
    r = 0.5f * (a_s * a_s + a_p * a_p);
  }
  *cos_t = outside ? -ct : ct;
  *eta_ti = e_ti;
  return r;
}

CO_INLINE float fresnel_dielectric_r(float cos_i, float eta) {
  float ct, eti;
  return fresnel_dielectric(cos_i, eta, &ct, &eti);
}

/* Schlick's approximation with a coloured F0: the glTF metallic workflow, where the conductor's
 * normal-incidence reflectance is the base colour. */
CO_INLINE co_vec3 fresnel_schlick(co_vec3 f0, float cos_i) {
  float c = fmin(fmax(1.0f - fabs(cos_i), 0.0f), 1.0f);
  float c2 = c * c;
  float w = c2 * c2 * c;
  return v3(f0.x + (1.0f - f0.x) * w, f0.y + (1.0f - f0.y) * w, f0.z + (1.0f - f0.z) * w);
}

/* Cosine-weighted hemispherical average of the dielectric Fresnel reflectance, F_dr(eta), as the
 * fits used by Mitsuba (Egan & Hilgeman 1973 for eta < 1, d'Eon & Irving 2011 otherwise; relative
 * error about 0.1% for IORs in [1, 2]). Used by the plastic model exactly as Mitsuba uses it. */
CO_INLINE float fresnel_diffuse_reflectance(float eta) {
  if (eta < 1.0f) return -1.4399f * (eta * eta) + 0.7099f * eta + 0.6681f + 0.0636f / eta;
  float i1 = 1.0f / eta, i2 = i1 * i1, i3 = i2 * i1, i4 = i3 * i1, i5 = i4 * i1;
  return 0.919317f - 3.4793f * i1 + 6.75335f * i2 - 7.80989f * i3 + 4.98554f * i4 - 1.36881f * i5;
}

/* ---- GGX ----------------------------------------------------------------------------------- */

/* Normal distribution D(m) for m in the upper hemisphere (isotropic alpha), Walter et al. eq. 33,
 * written as 1 / (pi a^2 (x^2/a^2 + y^2/a^2 + z^2)^2) which has no tan/cos singularities. */
CO_INLINE float ggx_d(co_vec3 m, float alpha) {
  if (m.z <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  float t = (m.x * m.x + m.y * m.y) / a2 + m.z * m.z;
  return 1.0f / (CO_PI * a2 * t * t);
}

/* Smith's Lambda for GGX (Heitz 2014, eq. 72): (-1 + sqrt(1 + a^2 tan^2 theta)) / 2. Depends on
 * |tan theta| only, so it serves both hemispheres. */
CO_INLINE float ggx_lambda(co_vec3 w, float alpha) {
  float z2 = w.z * w.z;
  if (z2 <= 0.0f) return INFINITY;
  float a2tan2 = alpha * alpha * (w.x * w.x + w.y * w.y) / z2;
  return 0.5f * (-1.0f + sqrt(1.0f + a2tan2));
}

/* Masking of one direction for microfacet m: 0 where m is back-facing as seen from w (the
 * "chi+" of Heitz 2014 eq. 43), for w on either side of the macro-surface. */
CO_INLINE float ggx_g1(co_vec3 w, co_vec3 m, float alpha) {
  if (v3_dot(w, m) * w.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + ggx_lambda(w, alpha));
}

/* Height-correlated masking-shadowing (Heitz 2014, eq. 99): 1 / (1 + Lambda(wi) + Lambda(wo)).
 * Chosen over the separable product G1 G1, which overestimates the shadowing of correlated
 * heights and so darkens rough surfaces more than the microsurface does. */
CO_INLINE float ggx_g2(co_vec3 wi, co_vec3 wo, co_vec3 m, float alpha) {
  if (v3_dot(wi, m) * wi.z <= 0.0f || v3_dot(wo, m) * wo.z <= 0.0f) return 0.0f;
  return 1.0f / (1.0f + ggx_lambda(wi, alpha) + ggx_lambda(wo, alpha));
}

/* Density of the visible normals seen from wi (wi.z > 0): D_wi(m) = G1(wi) max(0, wi.m) D(m) / wi.z
 * (Heitz 2018, eq. 1); it integrates to 1 over the hemisphere of m. */
CO_INLINE float ggx_vndf_pdf(co_vec3 wi, co_vec3 m, float alpha) {
  float dm = v3_dot(wi, m);
  if (!(wi.z > 0.0f) || dm <= 0.0f) return 0.0f;
  return ggx_g1(wi, m, alpha) * dm * ggx_d(m, alpha) / wi.z;
}

/* A visible normal seen from wi (wi.z > 0), Heitz 2018, listing 1: stretch wi to the hemisphere
 * configuration, sample the projected area of the half disk, reproject and unstretch. */
CO_INLINE co_vec3 ggx_sample_vndf(co_vec3 wi, float alpha, float u1, float u2) {
  co_vec3 vh = v3_normalize(v3(alpha * wi.x, alpha * wi.y, wi.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  co_vec3 t1 = lensq > 0.0f ? v3_scale(v3(-vh.y, vh.x, 0.0f), 1.0f / sqrt(lensq)) : v3(1.0f, 0.0f, 0.0f);
  co_vec3 t2 = v3_cross(vh, t1);
  float r = sqrt(u1);
  float sin_phi, cos_phi;
  co_sincos_2pi(u2, &sin_phi, &cos_phi);
  float p1 = r * cos_phi;
  float p2 = r * sin_phi;
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * co_safe_sqrt(1.0f - p1 * p1) + s * p2;
  float pz = co_safe_sqrt(1.0f - p1 * p1 - p2 * p2);
  co_vec3 nh = v3_add(v3_add(v3_scale(t1, p1), v3_scale(t2, p2)), v3_scale(vh, pz));
  return v3_normalize(v3(alpha * nh.x, alpha * nh.y, fmax(0.0f, nh.z)));
}

#endif
