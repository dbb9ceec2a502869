/* glTF KHR_lights_punctual point and spot lights (docs/lights.md): delta lights, so only
 * next-event estimation reaches them (a BSDF-sampled ray never hits one; no MIS). Intensity is
 * in candela, taken as W/sr of the renderer's radiometric units (as Mitsuba's `point` and `spot`
 * intensity); `range` is ignored (inverse-square falloff everywhere). */
#ifndef COHORT_PUNCTUAL_H
#define COHORT_PUNCTUAL_H

#include "common/core/types.h"
#include "common/core/vec.h"

/* The light whose cdf step holds u (binary search). */
CO_INLINE uint32_t pick_punctual(const CO_GLOBAL PunctualLight* lights, uint32_t count, float u) {
  uint32_t lo = 0u, hi = count - 1u;
  while (lo < hi) {
    uint32_t mid = (lo + hi) >> 1;
    if (u < lights[mid].cdf) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

/* glTF's spot falloff: a smooth step between the cosines of the outer and inner cone angles,
 * squared (the specification's reference implementation); 1 for a point light. */
CO_INLINE float punctual_falloff(const CO_GLOBAL PunctualLight* l, co_vec3 to_receiver) {
  if (l->type != PUNCTUAL_SPOT) return 1.0f;
  float cos_outer = l->direction.w, cos_inner = l->intensity.w;
  float scale = 1.0f / fmax(0.001f, cos_inner - cos_outer);
  float cd = v3_dot(v3_from4(l->direction), to_receiver);
  float a = fmin(fmax(cd * scale - cos_outer * scale, 0.0f), 1.0f);
  return a * a;
}

/* Intensity (rgb, W/sr) the light sends along the unit direction `to_receiver`. */
CO_INLINE co_vec3 punctual_intensity(const CO_GLOBAL PunctualLight* l, co_vec3 to_receiver) {
  return v3_scale(v3_from4(l->intensity), punctual_falloff(l, to_receiver));
}

#endif
