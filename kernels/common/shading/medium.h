/* Homogeneous absorbing media behind transmissive surfaces (glTF KHR_materials_volume; docs/bsdf.md,
 * "Volumes"): radiance travelling a distance d inside is multiplied by exp(-sigma_a d) per RGB
 * channel (Beer-Lambert). Plain C for OpenCL C 1.2, CUDA and host C++. */
#ifndef COHORT_MEDIUM_H
#define COHORT_MEDIUM_H

#include "common/core/types.h"
#include "common/core/vec.h"

/* e^x from adds, multiplies, floor and bit operations only, so the host and every device round it
 * identically (the built-in exp may differ by a few ulp between PoCL, NVIDIA's OpenCL and CUDA, as
 * sin and cos do; microfacet.h). Cody-Waite reduction x = k ln2 + r with fdlibm's split of ln 2
 * (ln2_hi has 17 significant bits, so k ln2_hi is exact for |k| < 128, and x - k ln2_hi is exact),
 * r in [-ln2/2, ln2/2], where the Taylor polynomial to r^7 is accurate to about 1 ulp; 2^k is built
 * from its exponent bits. Below -86 it returns 0: e^-86 (4e-38) is near the smallest normal float,
 * and 0 there keeps every result normal, so no device's flushing of subnormals can tell them apart.
 * Medium transmittance needs x <= 0 only; above 88 it returns infinity. NaN stays NaN. */
CO_INLINE float co_exp(float x) {
  if (x != x) return x;
  if (!(x >= -86.0f)) return 0.0f;
  if (x > 88.0f) return INFINITY;
  float k = floor(x * 0x1.715476p+0f + 0.5f); /* nearest integer to x / ln 2 */
  float r = (x - k * 0x1.62e300p-1f) - k * 0x1.2fefa2p-17f;
  float p = 1.0f + r * (1.0f + r * (0.5f + r * (1.0f / 6.0f + r * (1.0f / 24.0f + r * (1.0f / 120.0f +
                  r * (1.0f / 720.0f + r * (1.0f / 5040.0f)))))));
  return p * co_as_float((uint32_t)((int32_t)k + 127) << 23);
}

/* exp(-sigma d) of one channel: 1 for a channel that does not absorb (also over an infinite
 * distance, where sigma d would be NaN), 0 for an absorbing one over an infinite distance. */
CO_INLINE float medium_transmittance1(float sigma, float d) {
  return sigma > 0.0f ? co_exp(-(sigma * d)) : 1.0f;
}

CO_INLINE co_vec3 medium_transmittance(co_vec3 sigma, float d) {
  return v3(medium_transmittance1(sigma.x, d), medium_transmittance1(sigma.y, d), medium_transmittance1(sigma.z, d));
}

/* A path's medium: MEDIUM_NONE outside every volume, else 1 + the index of the material whose
 * interior it is in (kept as a float in a free lane of the path slot, exact below 2^24). */
#define MEDIUM_NONE 0u

CO_INLINE int material_absorbs(const CO_GLOBAL Material* m) {
  return m->absorption.x > 0.0f || m->absorption.y > 0.0f || m->absorption.z > 0.0f;
}

/* The medium beyond a vertex on material `material` (index `id`) in a direction that crosses the
 * surface (`crosses`: a refraction, or a shadow ray through a transmissive surface) or not, and
 * leaves from its back (`back`: the side opposite the geometric normal, the interior). A crossing
 * into the back enters the material's volume (or none when it does not absorb), a crossing to the
 * front leaves it for the outside; a reflection stays in the medium it came from. Exact for closed,
 * non-nested volumes with the camera outside (docs/bsdf.md). */
CO_INLINE uint32_t medium_beyond(uint32_t current, const CO_GLOBAL Material* m, uint32_t id, int crosses, int back) {
  if (!crosses) return current;
  return (back && material_absorbs(m)) ? id + 1u : MEDIUM_NONE;
}

#endif
