/* glTF alphaMode for every ray (COHORT_FEATURE_ALPHA; a scene without a MASK or BLEND material
 * compiles none of this). A surface's alpha at a hit is baseColorFactor.a times the base colour
 * texture's alpha times COLOR_0's alpha, at the hit's barycentrics:
 *   MASK   the hit is cut out where alpha < alphaCutoff;
 *   BLEND  stochastic transparency: the hit is skipped with probability 1 - alpha, so a surface
 *          hit is shaded opaque with probability alpha and the estimate is unbiased in expectation;
 *   OPAQUE alpha is never read.
 * A skipped hit is as if the triangle were not there: consider_triangle (kdtree_traverse.h), which
 * every traversal (KD-tree, BVH4, their PTH resumes, the speculative walk; closest and any hit) goes
 * through, never records it. The BLEND decision is a hash of the ray's seed (the path's seed,
 * pixel, sample and segment, and whether it is the segment's extension or shadow ray) and the kept
 * triangle's index, nothing else: whichever tree and order meet the triangle, and however often
 * (a triangle referenced from several leaves), the ray gets the same answer for it, so the closest
 * hit and the image stay the same bits on every tree and method. */
#ifndef COHORT_ALPHA_H
#define COHORT_ALPHA_H

/* Included unconditionally: the host expands each kernel header once, at its first #include,
 * whatever #if surrounds it. */
#include "common/accel/alpha_view.h"
#include "common/core/rng.h"
#include "common/shading/texture.h"

#if defined(COHORT_FEATURE_ALPHA)

/* The seed a ray's BLEND decisions hash from: 24 bits, so that the wavefront kernels can keep it
 * exactly in a float (the w of a ray origin) between launches (alpha_seed_to_float). */
CO_INLINE uint32_t alpha_ray_seed(uint32_t path_key, uint32_t segment, uint32_t purpose) {
  return rng_at(path_key, segment, purpose).state >> 8;
}
#endif
/* the sheen roughness and specular textures read the alpha channel too (scene_view.h, sheen_params and
 * specular_params) */
#if (defined(COHORT_FEATURE_ALPHA) || defined(COHORT_FEATURE_SHEEN) || defined(COHORT_FEATURE_SPECULAR)) && \
    defined(COHORT_FEATURE_TEXTURES)
/* The alpha channel (linear in glTF, never sRGB) of texture `index` at (u, v), filtered and
 * wrapped exactly as texture_sample filters the colour channels (the same footprint). */
CO_INLINE float texel_alpha(const CO_GLOBAL uint32_t* texels, uint32_t index) {
  return (float)(texels[index] >> 24) * (1.0f / 255.0f);
}

CO_INLINE float texture_sample_alpha(const CO_GLOBAL TextureDesc* descs, const CO_GLOBAL uint32_t* texels,
                                     int32_t index, float u, float v) {
  TexelFootprint f = texture_footprint(descs, index, u, v);
  if (f.nearest) return texel_alpha(texels, f.row0 + f.x0);
  float a = texel_alpha(texels, f.row0 + f.x0) * (1.0f - f.tx) + texel_alpha(texels, f.row0 + f.x1) * f.tx;
  float b = texel_alpha(texels, f.row1 + f.x0) * (1.0f - f.tx) + texel_alpha(texels, f.row1 + f.x1) * f.tx;
  return a * (1.0f - f.ty) + b * f.ty;
}
#endif
#if defined(COHORT_FEATURE_ALPHA)

/* The material's alpha at barycentric weights (b1, b2) of kept triangle `triangle`. */
CO_INLINE float material_alpha(const AlphaView* a, const CO_GLOBAL Material* m, uint32_t triangle, float b1,
                               float b2) {
  float alpha = m->base_color.w;
#ifdef COHORT_FEATURE_TEXTURES
  if (m->base_color_texture >= 0) {
    float u, v;
    slot_uv_at(a->triangle_uvs, (m->flags & MAT_UV1_BASE_COLOR) != 0u, triangle, b1, b2, &u, &v);
    alpha = alpha * texture_sample_alpha(a->textures, a->texels, m->base_color_texture, u, v);
  }
#endif
#ifdef COHORT_FEATURE_VERTEX_COLORS
  {
    TriangleColor c = a->triangle_colors[triangle];
    alpha = alpha * ((1.0f - b1 - b2) * c.c0.w + b1 * c.c1.w + b2 * c.c2.w);
  }
#endif
  (void)a;
  (void)triangle;
  (void)b1;
  (void)b2;
  return alpha;
}

/* How much of the surface is there at (b1, b2), in expectation: 1 for OPAQUE, 0 or 1 for MASK,
 * alpha (clamped to [0, 1]) for BLEND. Next-event estimation scales an emitter's light by it,
 * which is what the rays that meet the emitter see on average. */
CO_INLINE float alpha_coverage(const AlphaView* a, const CO_GLOBAL Material* m, uint32_t triangle, float b1, float b2) {
  uint32_t mode = m->flags & (MAT_ALPHA_MASK | MAT_ALPHA_BLEND);
  if (mode == 0u) return 1.0f;
  float alpha = material_alpha(a, m, triangle, b1, b2);
  if (mode == MAT_ALPHA_MASK) return alpha >= m->alpha_cutoff ? 1.0f : 0.0f;
  return fmin(fmax(alpha, 0.0f), 1.0f);
}

/* A uniform number in [0, 1) for the ray with `seed` meeting kept triangle `triangle`. */
CO_INLINE float alpha_uniform(uint32_t seed, uint32_t triangle) {
  return (float)(pcg_hash(pcg_hash(seed ^ 0x2545f491u) ^ triangle) >> 8) * (1.0f / 16777216.0f);
}

/* 1 when the ray with `seed` goes through kept triangle `triangle` at (b1, b2) (declared in
 * alpha_view.h, for consider_triangle). */
CO_INLINE int alpha_skips(const AlphaView* a, uint32_t seed, uint32_t triangle, float b1, float b2) {
  const CO_GLOBAL Material* m = &a->materials[a->triangle_material[triangle]];
  uint32_t mode = m->flags & (MAT_ALPHA_MASK | MAT_ALPHA_BLEND);
  if (mode == 0u) return 0;
  float alpha = material_alpha(a, m, triangle, b1, b2);
  if (mode == MAT_ALPHA_MASK) return !(alpha >= m->alpha_cutoff);
  return !(alpha_uniform(seed, triangle) < alpha);
}

#endif

#endif
