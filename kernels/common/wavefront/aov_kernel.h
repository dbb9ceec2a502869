/* First-hit AOVs (docs/decisions.md): the glTF base colour (times its texture) as albedo, the
 * world-space normal the shading frame uses (flat: the stored geometric normal) and the distance
 * along the camera ray. One work item per pixel traces the camera rays of this launch's samples,
 * the very rays path_start gives the beauty's samples, and adds them to its sums in sample order:
 * the AOVs are the same bits whatever method rendered the beauty and however the samples were
 * split into launches. A pixel stops at its own sample count (aov_samples: adaptive sampling's
 * pixels differ), so its AOVs average the samples its beauty has.
 *
 * albedo: rgb summed over the samples (an escaped ray adds 0), w the depth summed over the
 * samples that hit; normal: xyz summed likewise, w the number of samples that hit. */
#ifndef COHORT_AOV_KERNEL_H
#define COHORT_AOV_KERNEL_H

#include "common/core/kernel_params.h"
#include "common/wavefront/pathtrace.h"

CO_KERNEL render_aov(CO_PARAMS(RENDER_AOV_PARAMS)) {
  uint32_t pixel = co_global_id();
  RenderParams p = *params;
  if (pixel >= p.width * p.height) return;
  SceneView s = SCENE_VIEW(p);

  co_float4 albedo = aov_albedo[pixel];
  co_float4 normal = aov_normal[pixel];
  uint32_t own = aov_samples[pixel];
  uint32_t count = own > p.sample_offset ? own - p.sample_offset : 0u;
  if (count > p.samples_per_pass) count = p.samples_per_pass;
  for (uint32_t i = 0u; i < count; ++i) {
    PathState st = path_start(&p, pixel, rng_path_key(p.seed, pixel, p.sample_offset + i));
    HitOut hit = scene_trace_steps(&s.tree, st.org, st.dir, 0.0f, INFINITY, 0, 0 CO_ALPHA_ARG(st.alpha_seed));
    if (hit.triangle == HIT_NONE) continue;
    const CO_GLOBAL Material* m = &s.materials[s.triangle_material[hit.triangle]];
    co_vec3 base_color =
        surface_params(&s, m, hit.triangle, hit.u, hit.v).base_color;
    co_vec3 n = v3_normalize(triangle_cross(&s.triangles[hit.triangle]));
#ifdef COHORT_FEATURE_NORMAL_MAP
    n = mapped_normal(&s, m, hit.triangle, hit.u, hit.v, n);
#endif
    albedo = film_add(albedo, base_color);
    albedo.w = albedo.w + hit.t; /* the camera ray's direction is a unit vector: t is the distance */
    normal = film_add(normal, n);
    normal.w = normal.w + 1.0f;
  }
  aov_albedo[pixel] = albedo;
  aov_normal[pixel] = normal;
}

#endif
