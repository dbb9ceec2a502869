/* glTF KHR_materials_specular in the path tracer (docs/bsdf.md, "Specular"), compiled into rendering
 * programs only with COHORT_FEATURE_SPECULAR. Plain C for OpenCL C 1.2, CUDA and host C++.
 * glTF mixes the dielectric's diffuse base and its specular reflection by a re-shaped Fresnel term,
 *   f = (1 - max3 F(cos_i)) f_diffuse(baseColor) + F f_specular,
 *   F = f0' + (f90' - f0') s,   f0' = min(f0(ior) specularColor, 1) specular,   f90' = specular,
 * with s the exact dielectric Fresnel's shape (BSDF_SPECULAR, bsdf.h; glTF writes Schlick's). One BSDF
 * is chosen per shading point: the tinted reflection (BSDF_SPECULAR) with probability q = max3 F(|cos_i|),
 * scaled by 1 / q, else the Lambertian with the base colour, whose weight (1 - max3 F) / (1 - q) is then
 * exactly 1. The expectation is glTF's mix; specular = 0 is exactly the Lambertian. */
#ifndef COHORT_SPECULAR_H
#define COHORT_SPECULAR_H

#include "common/shading/bsdf.h"

/* u_select of bsdf_from_gltf remapped to [0, 1) given "neither metal nor transmissive", the share of
 * u_select its opaque dielectric takes, for the layering's own choice. */
CO_INLINE float gltf_opaque_u(float metallic, float transmission, float u_select) {
  float met = fmin(fmax(metallic, 0.0f), 1.0f);
  float u = met > 0.0f ? (u_select - met) / (1.0f - met) : u_select;
  if (transmission > 0.0f) u = (u - transmission) / (1.0f - transmission);
  return fmin(fmax(u, 0.0f), 0x1.fffffep-1f);
}

/* The layering at a shading point of glTF roughness `roughness` and IOR `ior` (outside [1, 10]: 1.5,
 * as bsdf_from_gltf), specularColor `color` (>= 0) and specular factor `specular` (clamped to [0, 1]),
 * seen from wi (local; either side: the lobe and the base are two-sided), chosen by u in [0, 1).
 * Every roughness, 1 included, takes the GGX lobe (bsdf_from_gltf's roughness-1 Lambertian is for
 * materials without the extension). */
CO_INLINE Bsdf bsdf_specular_layer(co_vec3 base_color, float roughness, float ior, co_vec3 color, float specular,
                                   co_vec3 wi, float u) {
  float eta = (ior >= 1.0f && ior <= 10.0f) ? ior : 1.5f;
  float w = fmin(fmax(specular, 0.0f), 1.0f);
  float r = (eta - 1.0f) / (eta + 1.0f);
  float f0 = r * r;
  co_vec3 f0_tint = v3(fmin(f0 * fmax(color.x, 0.0f), 1.0f) * w, fmin(f0 * fmax(color.y, 0.0f), 1.0f) * w,
                       fmin(f0 * fmax(color.z, 0.0f), 1.0f) * w);
  float q = v3_max_component(specular_fresnel(f0_tint, w, fabs(wi.z), eta));
  if (u < q) {
    float rough = fmin(fmax(roughness, 0.0f), 1.0f);
    return bsdf_specular(eta, rough * rough, f0_tint, w, 1.0f / q);
  }
  return bsdf_diffuse(base_color);
}

/* The BSDF of a material with the extension, given `b`, the one bsdf_from_gltf chose from u_select
 * (at the same parameters): the metal and the transmissive dielectric stay (the specular factors do not
 * reach them; docs/bsdf.md says why), the opaque dielectric becomes the layering, chosen from the rest
 * of u_select. */
CO_INLINE Bsdf bsdf_specular_base(Bsdf b, co_vec3 base_color, float metallic, float roughness, float transmission,
                                  float ior, co_vec3 color, float specular, co_vec3 wi, float u_select) {
  if (b.type != BSDF_PLASTIC && b.type != BSDF_DIFFUSE) return b;
  return bsdf_specular_layer(base_color, roughness, ior, color, specular, wi,
                             gltf_opaque_u(metallic, transmission, u_select));
}

#endif
