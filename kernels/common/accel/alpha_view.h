/* What the traversal needs of glTF alpha modes before the scene's other headers (intersect.h
 * includes it): the arrays an alpha test reads, the test's declaration (alpha.h defines it, after the
 * texture lookups it uses) and the traversal functions' extra parameter, the ray's alpha seed. A
 * program built without COHORT_FEATURE_ALPHA gets none of it: every macro below expands to nothing. */
#ifndef COHORT_ALPHA_VIEW_H
#define COHORT_ALPHA_VIEW_H

#include "common/core/types.h"

#if defined(COHORT_FEATURE_ALPHA)

/* The scene arrays an alpha test reads; the traversal views carry one (scene_view.h sets it). */
typedef struct AlphaView {
  const CO_GLOBAL uint32_t* triangle_material; /* per kept triangle */
  const CO_GLOBAL Material* materials;
  const CO_GLOBAL TriangleUv* triangle_uvs;
  const CO_GLOBAL TextureDesc* textures;
  const CO_GLOBAL uint32_t* texels;
#ifdef COHORT_FEATURE_VERTEX_COLORS
  const CO_GLOBAL TriangleColor* triangle_colors;
#endif
} AlphaView;

/* 1 when the ray with `seed` goes through kept triangle `triangle` at (b1, b2) (alpha.h). */
CO_INLINE int alpha_skips(const AlphaView* a, uint32_t seed, uint32_t triangle, float b1, float b2);

/* The wavefront kernels keep a ray's 24-bit alpha seed in the w of its origin, exactly. */
CO_INLINE float alpha_seed_to_float(uint32_t seed) { return (float)seed; }
CO_INLINE uint32_t alpha_seed_from_float(float f) { return (uint32_t)f; }

/* Extra trailing parameter and argument of the traversal functions: the ray's seed. */
#define CO_ALPHA_PARAM , uint32_t alpha_seed
#define CO_ALPHA_ARG(seed) , (seed)

#else

#define CO_ALPHA_PARAM
#define CO_ALPHA_ARG(seed)

#endif

#endif
