/* glTF KHR_materials_clearcoat in the path tracer (docs/bsdf.md, "Clearcoat"), compiled only with
 * COHORT_FEATURE_CLEARCOAT. glTF layers the coat over the whole material,
 *   f = (1 - c F(cos_i)) f_base + c f_coat,
 * with c the clearcoat factor (times its texture's R) and the coat a GGX reflection of a dielectric
 * of IOR 1.5 and alpha = clearcoatRoughness^2 about the coat's own normal. One BSDF is chosen per
 * shading point: the coat with probability q = c F(cos_i) (F the exact Fresnel, cos_i about the coat's
 * normal), scaled by c / q, else the base as bsdf_from_gltf picks it from the rest of u_select. The
 * base's weight (1 - c F) / (1 - q) is then exactly 1 and the coat's estimate is c f_coat. */
#ifndef COHORT_CLEARCOAT_H
#define COHORT_CLEARCOAT_H

#include "common/shading/bsdf.h"
#include "common/accel/scene_view.h"

#define CLEARCOAT_ETA 1.5f /* glTF: the coat's IOR is fixed at 1.5 */

/* The outcome of the coat's choice at a shading point: when `chosen`, the coat's BSDF, its frame
 * and wi in that frame replace the base's; otherwise u_rest is u_select remapped to [0, 1) given
 * "not the coat", for bsdf_from_gltf. */
typedef struct CoatChoice {
  int chosen;
  float u_rest;
  Bsdf bsdf;
  ShadingFrame frame;
  co_vec3 wi;
} CoatChoice;

/* The coat of `material` at (b1, b2) of `triangle`, seen along the ray direction `dir`. The coat's
 * normal is the surface's (n_geo), or its clearcoatNormalTexture's (glTF: the base's normal map does
 * not bend the coat), dropped for n_geo where it would put dir on the other side, as the base's is. */
CO_INLINE CoatChoice coat_choose(const SceneView* s, uint32_t material, uint32_t triangle, float b1, float b2,
                                 co_vec3 n_geo, co_vec3 dir, float u_select) {
  CoatChoice r;
  r.chosen = 0;
  r.u_rest = u_select;
  const CO_GLOBAL MaterialCoat* c = &s->material_coats[material];
  if (!(c->factor > 0.0f)) return r;
  float weight = c->factor;
  if (c->factor_texture >= 0) weight = weight * slot_texture(s, c->factor_texture, (c->flags & COAT_UV1_FACTOR) != 0u, triangle, b1, b2).x;
  weight = fmin(weight, 1.0f);
  r.frame = frame_from_normal(n_geo);
#ifdef COHORT_FEATURE_NORMAL_MAP
  if (c->normal_texture >= 0) {
    co_vec3 ns = tangent_space_normal(s, triangle, b1, b2, n_geo,
                                      slot_texture(s, c->normal_texture, (c->flags & COAT_UV1_NORMAL) != 0u, triangle, b1, b2),
                                      c->normal_scale);
    if (v3_dot(ns, dir) * v3_dot(n_geo, dir) > 0.0f) {
      r.frame = frame_from_normal(ns);
      r.frame.ng = n_geo;
    }
  }
#endif
  r.wi = frame_to_local(&r.frame, v3_neg(dir));
  float q = weight * fresnel_dielectric_r(fabs(r.wi.z), CLEARCOAT_ETA);
  if (!(u_select < q)) {
    r.u_rest = fmin(fmax((u_select - q) / (1.0f - q), 0.0f), 0x1.fffffep-1f);
    return r;
  }
  float roughness = c->roughness;
  if (c->roughness_texture >= 0)
    roughness = roughness * slot_texture(s, c->roughness_texture, (c->flags & COAT_UV1_ROUGHNESS) != 0u, triangle, b1, b2).y;
  roughness = fmin(fmax(roughness, 0.0f), 1.0f);
  r.chosen = 1;
  r.bsdf = bsdf_coat(CLEARCOAT_ETA, roughness * roughness, weight / q);
  return r;
}

#endif
