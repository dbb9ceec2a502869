/* NAIVE: the reference megakernel. One work item per pixel of the pass traces this pass's samples of its
 * pixel in sample order and adds each to the film in that order, so the film is the same sum
 * whatever the work-group size or device scheduling. */
#ifndef COHORT_NAIVE_KERNEL_H
#define COHORT_NAIVE_KERNEL_H

#include "common/core/kernel_params.h"
#include "common/wavefront/pathtrace.h"
#include "common/wavefront/shade_batch.h"

/* A sample's path into the pixel's sum and the counters. A NaN or infinite sample never reaches the
 * image; it counts as a zero sample. */
CO_INLINE void naive_add_sample(co_float4* acc, uint32_t* rays, uint32_t* max_steps, uint32_t* dropped, PathResult r) {
  *rays += r.rays;
  *max_steps = co_umax(*max_steps, r.max_steps);
  if (v3_is_finite(r.radiance))
    *acc = film_add_sample(*acc, r.radiance);
  else
    *dropped += 1u;
}

CO_KERNEL render_naive(CO_PARAMS(RENDER_NAIVE_PARAMS)) {
  uint32_t k = co_global_id();
  RenderParams p = *params;
  if (k >= pass_pixel_count(&p)) return;
  uint32_t pixel = pass_pixel(k, pixel_list, &p);
  SceneView s = SCENE_VIEW(p);

  co_float4 acc = film[pixel];
  uint32_t rays = 0u, dropped = 0u, max_steps = 0u;
#if defined(COHORT_NAIVE_PAIRS)
  /* A pixel none of whose rays can meet the scene (the background of a view from outside): under a
   * constant sky every sample is the same path, which leaves at once (trace_path_outside: what a
   * camera ray outside the scene's box gives, or one inside it that meets no triangle), added as
   * often as the pixel has samples, in order, without a camera ray, a hash or a division each. */
  const int background = !(p.flags & RENDER_FLAG_ENVIRONMENT_MAP) &&
                         camera_pixel_misses_box(&p.camera, p.width, p.height, pixel % p.width, pixel / p.width,
                                                 v3_from4(p.scene_min), v3_from4(p.scene_max));
  if (background) {
    const uint32_t key = rng_path_key(p.seed, pixel, p.sample_offset);
    const PathResult sky = trace_path_outside(&s, &p, path_start(&p, pixel, key), key);
    for (uint32_t i = 0u; i < p.samples_per_pass; ++i) naive_add_sample(&acc, &rays, &max_steps, &dropped, sky);
  }
  for (uint32_t i = 0u; !background && i < p.samples_per_pass; i += PATH_START_BATCH) {
    uint32_t m = co_umin(PATH_START_BATCH, p.samples_per_pass - i), first = p.sample_offset + i;
    PathState start[PATH_START_BATCH];
    PathResult results[PATH_START_BATCH];
    uint32_t walked[PATH_START_BATCH], keys[PATH_START_BATCH], n = 0u;
    uint32_t outside = path_start_batch(&p, pixel, first, start, keys);
    /* camera rays that miss the scene end at once; the others walk the tree as one packet (where
     * they share an octant, else each alone), then their paths go on in pairs (trace_paths_paired),
     * and every sample reaches the film in sample order */
    for (uint32_t j = 0u; j < m; ++j) {
      if ((outside >> j) & 1u)
        results[j] = trace_path_outside(&s, &p, start[j], keys[j]);
      else
        walked[n++] = j;
    }
    if (n != 0u) { /* a pixel of the background has none */
      Bvh8fPacket camera;
      bvh8f_packet_begin(&camera, start[walked[0]].dir);
      int one_octant = 1;
      for (uint32_t j = 1u; j < n; ++j) one_octant &= bvh8f_packet_fits(&camera, start[walked[j]].dir);
      if (one_octant) {
        /* the rays' set-ups side by side (bvh8f_packet_add_all); lanes from n on repeat the first */
        float ox[BVH8F_PACKET], oy[BVH8F_PACKET], oz[BVH8F_PACKET];
        float dx[BVH8F_PACKET], dy[BVH8F_PACKET], dz[BVH8F_PACKET];
#if defined(COHORT_FEATURE_ALPHA)
        uint32_t seeds[BVH8F_PACKET];
#endif
        for (uint32_t j = 0u; j < BVH8F_PACKET; ++j) {
          const PathState* st = &start[walked[j < n ? j : 0u]];
          ox[j] = st->org.x; oy[j] = st->org.y; oz[j] = st->org.z;
          dx[j] = st->dir.x; dy[j] = st->dir.y; dz[j] = st->dir.z;
#if defined(COHORT_FEATURE_ALPHA)
          seeds[j] = st->alpha_seed;
#endif
        }
        bvh8f_packet_add_all(&s.tree, &camera, n, ox, oy, oz, dx, dy, dz CO_ALPHA_ARG(seeds));
        bvh8f_trace_packet(&s.tree, &camera);
      } else {
        for (uint32_t j = 0u; j < n; ++j) {
          const PathState* st = &start[walked[j]];
          camera.hit[j] = scene_trace_steps(&s.tree, st->org, st->dir, 0.0f, INFINITY, 0,
                                            &camera.count[j] CO_ALPHA_ARG(st->alpha_seed));
        }
      }
      /* in Lambertian-only programs the hits shaded eight to a vector (shade_batch.h), else in pairs */
      const int traced = n >= 2u && trace_paths_diffuse(&s, &p, n, walked, keys, camera.hit, camera.count, start, results);
      if (!traced && n >= 2u)
        trace_paths_paired(&s, &p, n, walked, start, keys, camera.hit, camera.count, 0, results);
      else if (!traced)
        results[walked[0]] =
            trace_path_from_hit(&s, &p, start[walked[0]], camera.hit[0], camera.count[0], keys[walked[0]]);
    }
    for (uint32_t j = 0u; j < m; ++j) naive_add_sample(&acc, &rays, &max_steps, &dropped, results[j]);
  }
#else
  for (uint32_t i = 0u; i < p.samples_per_pass; ++i)
    naive_add_sample(&acc, &rays, &max_steps, &dropped, trace_path(&s, &p, pixel, p.sample_offset + i));
#endif
  film[pixel] = acc;
  CO_GLOBAL uint32_t* slot = &counters[(co_group_id() % NAIVE_COUNTER_SLOTS) * NAIVE_COUNTER_STRIDE];
  co_atomic_add(&slot[NAIVE_COUNTER_RAYS], rays);
  co_atomic_max(&slot[NAIVE_COUNTER_MAX_STEPS], max_steps);
  if (dropped) co_atomic_add(dropped_samples, dropped);
}

#endif
