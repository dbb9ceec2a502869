/* Wavefront path tracing (Laine, Karras & Aila 2013): a pool of path slots in structure-of-arrays
 * buffers and one small kernel per stage. The methods differ only in which slots a launch covers
 * (all slots, or a compacted queue of live ones: stream compaction) and in when free slots take
 * new paths (when the whole pool is idle, or after every bounce: path regeneration). Every stage
 * calls the functions the NAIVE megakernel calls, in the same order per path, so every method
 * computes the reference radiance bit for bit; results land per work item and are added to the
 * film in sample order by wf_accumulate. */
#ifndef COHORT_WAVEFRONT_KERNELS_H
#define COHORT_WAVEFRONT_KERNELS_H

#include "common/wavefront/wavefront_path.h"

/* Free slots take the next work items (pixel, sample) of the pass; in queue mode they join the
 * queue of live slots. */
CO_KERNEL wf_generate(CO_PARAMS(WF_GENERATE_PARAMS)) {
  uint32_t slot = co_global_id();
  /* without regeneration the pool refills only once every path has ended; and the item counter
   * stops growing once the pass's items are handed out (it would wrap in long passes). Both tests
   * are the same for every work item: checked first, they make a launch with nothing to do cheap.
   * Both read words no work item of this launch writes (written by earlier launches), so they are
   * plain reads: an atomic read of COUNTER_NEXT_ITEM by every work item serialises the launch
   * (3.6 ms per launch of 4M on the H200 instead of microseconds). */
  if (!regenerate && counters[COUNTER_SURVIVED] != 0u) return;
  if (counters[COUNTER_ITEMS_HANDED] >= item_end) return;
  if (slot >= slot_count || path_item[slot] != ITEM_NONE) return;
  uint32_t item = co_atomic_inc(&counters[COUNTER_NEXT_ITEM]);
  if (item >= item_end) return;
  RenderParams p = *params;
  const uint32_t pixel = pixel_of(item, pixel_list, &p);
  PathState st = path_start(&p, pixel, rng_path_key(p.seed, pixel, sample_of(item, &p)));
  path_item[slot] = item;
  store_path(PATH_ARGS, slot, &st);
  uint32_t index = co_atomic_inc(&counters[COUNTER_QUEUE]); /* live slots, queue or not */
  if (use_queue) queue[index] = slot;
}

/* Closest hit of every live path's next ray. */
CO_KERNEL wf_extend(CO_PARAMS(WF_EXTEND_PARAMS)) {
  uint32_t i = co_global_id();
  if (i >= launch_count(count, counters, use_queue)) return;
  uint32_t slot = slot_of(i, queue, use_queue);
  uint32_t visited = 0u;
  if (path_item[slot] != ITEM_NONE && path_status[slot] == PATH_ALIVE) {
    RenderParams p = *params;
    SceneView s = SCENE_VIEW(p);
    hits[slot] = scene_trace_steps(&s.tree, v3_from4(path_org[slot]), v3_from4(path_dir[slot]), 0.0f, INFINITY, 0,
                                   &visited CO_ALPHA_ARG(alpha_seed_from_float(path_org[slot].w)));
  }
  steps[i] = visited; /* nodes visited per launch index: the SIMD efficiency figure */
}

/* Emission, light sample (queued as a shadow ray), Russian roulette and the next direction. */
CO_KERNEL wf_shade(CO_PARAMS(WF_SHADE_PARAMS)) {
  uint32_t i = co_global_id();
  if (i >= launch_count(count, counters, use_queue)) return;
  uint32_t slot = slot_of(i, queue, use_queue);
  uint32_t item = path_item[slot];
  if (item == ITEM_NONE || path_status[slot] != PATH_ALIVE) return;
  RenderParams p = *params;
  SceneView s = SCENE_VIEW(p);
  PathState st = load_path(PATH_ARGS, slot);
  /* a path that escapes draws no random number: its stream key is made only at a hit */
  const HitOut hit = hits[slot];
  const uint32_t key =
      hit.triangle != HIT_NONE ? rng_path_key(p.seed, pixel_of(item, pixel_list, &p), sample_of(item, &p)) : 0u;
  ShadowRay sr = path_shade(&s, &p, &st, hit, key);
  store_path(PATH_ARGS, slot, &st);
  if (sr.valid) {
#if defined(COHORT_FEATURE_ALPHA)
    shadow_org[slot] = to4(sr.org, alpha_seed_to_float(sr.alpha_seed));
#else
    shadow_org[slot] = to4(sr.org, 0.0f);
#endif
    shadow_dir[slot] = to4(sr.dir, sr.tmax);
    shadow_contribution[slot] = to4(sr.contribution, 0.0f);
    shadow_queue[co_atomic_inc(&counters[COUNTER_SHADOW])] = slot;
  }
}

/* Any hit for each queued shadow ray; unoccluded light joins the path's radiance. */
CO_KERNEL wf_shadow(CO_PARAMS(WF_SHADOW_PARAMS)) {
  uint32_t i = co_global_id();
  if (i >= counters[COUNTER_SHADOW]) return;
  uint32_t slot = shadow_queue[i];
  RenderParams p = *params;
  SceneView s = SCENE_VIEW(p);
  co_float4 dir = shadow_dir[slot];
  uint32_t visited = 0u;
  HitOut occ = scene_trace_steps(&s.tree, v3_from4(shadow_org[slot]), v3_from4(dir), 0.0f, dir.w, 1,
                                 &visited CO_ALPHA_ARG(alpha_seed_from_float(shadow_org[slot].w)));
  steps[i] = visited; /* nodes visited per queue index: read by wf_shadow_max_steps */
  ShadowRay sr;
  sr.contribution = v3_from4(shadow_contribution[slot]);
  PathState st;
  st.radiance = v3_from4(path_radiance[slot]);
  path_resolve_shadow(&st, &sr, occ);
  path_radiance[slot] = to4(st.radiance, 0.0f);
}

/* Finished paths hand their radiance to the pass's result buffer and free their slot; live
 * paths are counted and, in queue mode, compacted into the queue (Wald 2011). */
CO_KERNEL wf_finish(CO_PARAMS(WF_FINISH_PARAMS)) {
  uint32_t slot = co_global_id();
  if (slot >= slot_count) return;
  uint32_t item = path_item[slot];
  if (item == ITEM_NONE) return;
  if (path_status[slot] == PATH_TERMINATED) {
    results[item] = path_radiance[slot];
    path_item[slot] = ITEM_NONE;
    return;
  }
  uint32_t index = co_atomic_inc(&counters[COUNTER_QUEUE]);
  /* one writer (the first survivor; wf_end_bounce zeroed the count): no race and no contended
   * atomic (every survivor exchanging the flag cost ~3 ms per launch of 4M on the H200) */
  if (index == 0u) counters[COUNTER_SURVIVED] = 1u;
  if (use_queue) queue[index] = slot;
}

/* Between shading and wf_finish, one work item: the bounce's figures into its row, and the
 * counters wf_finish and the next bounce count from zeroed. */
CO_KERNEL wf_end_bounce(CO_PARAMS(WF_END_BOUNCE_PARAMS)) {
  if (co_global_id() != 0u) return;
  CO_GLOBAL uint32_t *row = counters + COUNTER_COUNT + (bounce % BOUNCE_ROWS) * BOUNCE_FIGURES;
  row[BOUNCE_LIVE] = counters[COUNTER_QUEUE];
  row[BOUNCE_SHADOW] = counters[COUNTER_SHADOW];
  row[BOUNCE_SIMD_SUM] = counters[COUNTER_SIMD_SUM];
  row[BOUNCE_SIMD_GROUPS] = counters[COUNTER_SIMD_GROUPS];
  counters[COUNTER_QUEUE] = 0u;
  counters[COUNTER_SHADOW] = 0u;
  counters[COUNTER_SIMD_SUM] = 0u;
  counters[COUNTER_SIMD_GROUPS] = 0u;
  counters[COUNTER_SURVIVED] = 0u;
  counters[COUNTER_ITEMS_HANDED] = counters[COUNTER_NEXT_ITEM];
}

/* Adds the pass's samples to the film in sample order, as the megakernel does (work item k: the
 * pass's k-th pixel, whose results are items k, k + n, k + 2n, ...). */
CO_KERNEL wf_accumulate(CO_PARAMS(WF_ACCUMULATE_PARAMS)) {
  uint32_t k = co_global_id();
  RenderParams p = *params;
  uint32_t pixels = pass_pixel_count(&p);
  if (k >= pixels) return;
  uint32_t pixel = pass_pixel(k, pixel_list, &p);
  co_float4 acc = film[pixel];
  uint32_t dropped = 0u;
  for (uint32_t i = 0u; i < p.samples_per_pass; ++i) {
    co_vec3 r = v3_from4(results[i * pixels + k]);
    if (v3_is_finite(r))
      acc = film_add_sample(acc, r);
    else
      ++dropped;
  }
  film[pixel] = acc;
  if (dropped) co_atomic_add(dropped_samples, dropped);
}

/* Most nodes visited in each group of 32 consecutive launch indices, raised into the straggler
 * counter with one atomic per group. */
CO_INLINE uint32_t steps_group_max(CO_GLOBAL const uint32_t* steps, uint32_t first, uint32_t last,
                                   CO_GLOBAL uint32_t* counters, uint32_t* sum) {
  uint32_t most = 0u;
  *sum = 0u;
  for (uint32_t i = first; i < last; ++i) {
    *sum += steps[i];
    most = co_umax(most, steps[i]);
  }
  if (most > 0u) co_atomic_max(&counters[COUNTER_MAX_STEPS], most);
  return most;
}

/* SIMD efficiency of a traversal launch (Aila & Laine 2009): for each group of 32 consecutive
 * launch indices, mean over max of the nodes each visited; summed in units of 1e-4 with the
 * number of groups, so the host reads two counters instead of every step count. */
CO_KERNEL wf_simd_efficiency(CO_PARAMS(WF_SIMD_EFFICIENCY_PARAMS)) {
  uint32_t group = co_global_id();
  uint32_t first = group * SIMD_GROUP;
  count = launch_count(count, counters, use_queue);
  if (first >= count) return;
  uint32_t last = co_umin(first + SIMD_GROUP, count), sum = 0u;
  uint32_t most = steps_group_max(steps, first, last, counters, &sum);
  if (most == 0u) return;
  co_atomic_add(&counters[COUNTER_SIMD_SUM], (uint32_t)(10000.0f * (float)sum / (float)(most * (last - first)) + 0.5f));
  co_atomic_inc(&counters[COUNTER_SIMD_GROUPS]);
}

/* The shadow rays' share of the straggler counter (their count is on the device). */
CO_KERNEL wf_shadow_max_steps(CO_PARAMS(WF_SHADOW_MAX_STEPS_PARAMS)) {
  uint32_t first = co_global_id() * SIMD_GROUP, count = counters[COUNTER_SHADOW], sum = 0u;
  if (first >= count) return;
  steps_group_max(steps, first, co_umin(first + SIMD_GROUP, count), counters, &sum);
}

#endif
