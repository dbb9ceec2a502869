/* Wavefront path tracing (Laine, Karras & Aila 2013): a pool of path slots in structure-of-arrays
 * buffers and one small kernel per stage. The methods differ only in which slots a launch covers
 * (all slots, or a compacted queue of live ones: stream compaction) and in when free slots take
 * new paths (when the whole pool is idle, or after every bounce: path regeneration). Every stage
 * calls the functions the NAIVE megakernel calls, in the same order per path, so every method
 * computes the reference radiance bit for bit; results land per work item and are added to the
 * film in sample order by wf_accumulate. */
#include "wavefront_path.h"

/* Free slots take the next work items (pixel, sample) of the pass; in queue mode they join the
 * queue of live slots. */
__kernel void wf_generate(__constant RenderParams* params, PATH_PARAMS, __global uint* counters,
                          __global uint* queue, uint use_queue, uint slot_count, uint item_end) {
  uint slot = get_global_id(0);
  if (slot >= slot_count || path_item[slot] != ITEM_NONE) return;
  uint item = atomic_inc(&counters[COUNTER_NEXT_ITEM]);
  if (item >= item_end) return;
  RenderParams p = *params;
  PathState st = path_start(&p, pixel_of(item, &p), sample_of(item, &p));
  path_item[slot] = item;
  store_path(PATH_ARGS, slot, &st);
  if (use_queue) queue[atomic_inc(&counters[COUNTER_QUEUE])] = slot;
}

/* Closest hit of every live path's next ray. */
__kernel void wf_extend(SCENE_KERNEL_PARAMS, PATH_PARAMS, __global HitOut* hits, __global const uint* queue,
                        uint use_queue, uint count, __global uint* steps) {
  uint i = get_global_id(0);
  if (i >= count) return;
  uint slot = slot_of(i, queue, use_queue);
  uint visited = 0u;
  if (path_item[slot] != ITEM_NONE && path_status[slot] == PATH_ALIVE) {
    RenderParams p = *params;
    SceneView s = SCENE_VIEW(p);
    hits[slot] = kd_trace_steps(&s.tree, v3_from4(path_org[slot]), v3_from4(path_dir[slot]), 0.0f, INFINITY, 0,
                                &visited);
  }
  steps[i] = visited;  /* nodes visited per launch index: the SIMD efficiency figure */
}

/* Emission, light sample (queued as a shadow ray), Russian roulette and the next direction. */
__kernel void wf_shade(SCENE_KERNEL_PARAMS, PATH_PARAMS, __global const HitOut* hits, __global const uint* queue,
                       uint use_queue, uint count, __global float4* shadow_org, __global float4* shadow_dir,
                       __global float4* shadow_contribution, __global uint* shadow_queue, __global uint* counters) {
  uint i = get_global_id(0);
  if (i >= count) return;
  uint slot = slot_of(i, queue, use_queue);
  uint item = path_item[slot];
  if (item == ITEM_NONE || path_status[slot] != PATH_ALIVE) return;
  RenderParams p = *params;
  SceneView s = SCENE_VIEW(p);
  PathState st = load_path(PATH_ARGS, slot);
  ShadowRay sr = path_shade(&s, &p, &st, hits[slot], pixel_of(item, &p), sample_of(item, &p));
  store_path(PATH_ARGS, slot, &st);
  if (sr.valid) {
    shadow_org[slot] = to4(sr.org, 0.0f);
    shadow_dir[slot] = to4(sr.dir, sr.tmax);
    shadow_contribution[slot] = to4(sr.contribution, 0.0f);
    shadow_queue[atomic_inc(&counters[COUNTER_SHADOW])] = slot;
  }
}

/* Any hit for each queued shadow ray; unoccluded light joins the path's radiance. */
__kernel void wf_shadow(SCENE_KERNEL_PARAMS, __global float4* path_radiance, __global const float4* shadow_org,
                        __global const float4* shadow_dir, __global const float4* shadow_contribution,
                        __global const uint* shadow_queue, __global const uint* counters) {
  uint i = get_global_id(0);
  if (i >= counters[COUNTER_SHADOW]) return;
  uint slot = shadow_queue[i];
  RenderParams p = *params;
  SceneView s = SCENE_VIEW(p);
  float4 dir = shadow_dir[slot];
  HitOut occ = kd_trace(&s.tree, v3_from4(shadow_org[slot]), v3_from4(dir), 0.0f, dir.w, 1);
  ShadowRay sr;
  sr.contribution = v3_from4(shadow_contribution[slot]);
  PathState st;
  st.radiance = v3_from4(path_radiance[slot]);
  path_resolve_shadow(&st, &sr, occ);
  path_radiance[slot] = to4(st.radiance, 0.0f);
}

/* Finished paths hand their radiance to the pass's result buffer and free their slot; live
 * paths are counted and, in queue mode, compacted into the queue (Wald 2011). */
__kernel void wf_finish(PATH_PARAMS, __global float4* results, __global uint* counters, __global uint* queue,
                        uint use_queue, uint slot_count) {
  uint slot = get_global_id(0);
  if (slot >= slot_count) return;
  uint item = path_item[slot];
  if (item == ITEM_NONE) return;
  if (path_status[slot] == PATH_TERMINATED) {
    results[item] = path_radiance[slot];
    path_item[slot] = ITEM_NONE;
    return;
  }
  uint index = atomic_inc(&counters[COUNTER_QUEUE]);
  if (use_queue) queue[index] = slot;
}

/* Adds the pass's samples to the film in sample order, as the megakernel does. */
__kernel void wf_accumulate(__constant RenderParams* params, __global const float4* results, __global float4* film,
                            __global uint* dropped_samples) {
  uint pixel = get_global_id(0);
  RenderParams p = *params;
  uint pixels = p.width * p.height;
  if (pixel >= pixels) return;
  float4 acc = film[pixel];
  uint dropped = 0u;
  for (uint i = 0u; i < p.samples_per_pass; ++i) {
    co_vec3 r = v3_from4(results[i * pixels + pixel]);
    if (v3_is_finite(r)) acc += (float4)(r.x, r.y, r.z, 0.0f);
    else ++dropped;
  }
  film[pixel] = acc;
  if (dropped) atomic_add(dropped_samples, dropped);
}

/* SIMD efficiency of a traversal launch (Aila & Laine 2009): for each group of 32 consecutive
 * launch indices, mean over max of the nodes each visited; summed in units of 1e-4 with the
 * number of groups, so the host reads two counters instead of every step count. */
__kernel void wf_simd_efficiency(__global const uint* steps, uint count, __global uint* counters) {
  uint group = get_global_id(0);
  uint first = group * 32u;
  if (first >= count) return;
  uint last = min(first + 32u, count), sum = 0u, most = 0u;
  for (uint i = first; i < last; ++i) {
    sum += steps[i];
    most = max(most, steps[i]);
  }
  if (most == 0u) return;
  atomic_add(&counters[COUNTER_SIMD_SUM], (uint)(10000.0f * (float)sum / (float)(most * (last - first)) + 0.5f));
  atomic_inc(&counters[COUNTER_SIMD_GROUPS]);
}
