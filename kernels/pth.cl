/* The partial traversal heuristic pipeline (Wang & Deng, Figure 3) between regeneration and
 * shading: every live ray walks the top subtree in local memory and gets its coherence code;
 * the host sorts (code, slot) pairs on the device; pth_resume then continues each traversal in
 * sorted order from the state the walk left, so no node is visited twice and the hit equals a
 * full traversal's. With 0 levels the walk is empty and this is the hash sort of Garanzha & Loop
 * (method `hash`). */
#include "wavefront_path.h"
#include "common/coherence.h"

#define TRAVERSAL_DONE 0xffffffffu
#define PTH_MAX_LEVELS 16

__kernel void pth_walk_and_code(SCENE_KERNEL_PARAMS, __global const float4* path_org, __global const float4* path_dir,
                                __global const uint* path_item, __global const uint* path_status,
                                __global const uint* queue, uint use_queue, uint count, __local KdNode* subtree,
                                uint subtree_nodes, __constant CodeParams* code_params,
                                __global const float* origin_bounds, __global ulong* keys, __global uint* values,
                                __global uint4* traversal, __global float4* traversal_stack, uint stack_stride,
                                __global HitOut* hits) {
  /* one copy of the subtree per work-group, before any work item may leave */
  for (uint k = get_local_id(0); k < subtree_nodes; k += get_local_size(0)) subtree[k] = nodes[k];
  barrier(CLK_LOCAL_MEM_FENCE);
  uint i = get_global_id(0);
  if (i >= count) return;
  uint slot = slot_of(i, queue, use_queue);
  CodeParams c = *code_params;
  /* rays that are not traced this bounce sort last and are skipped by pth_resume */
  keys[i] = c.key_bits >= 64u ? ~(ulong)0 : (((ulong)1 << c.key_bits) - (ulong)1);
  values[i] = slot;
  if (path_item[slot] == ITEM_NONE || path_status[slot] != PATH_ALIVE) {
    traversal[slot] = (uint4)(TRAVERSAL_DONE, 0u, 0u, 0u);
    return;
  }
  RenderParams p = *params;
  SceneView s = SCENE_VIEW(p);
  co_vec3 org = v3_from4(path_org[slot]), dir = v3_from4(path_dir[slot]);
  co_vec3 inv_dir = kd_inverse(dir);
  float t0, t1;
  if (!kd_begin(&s.tree, org, inv_dir, 0.0f, INFINITY, &t0, &t1)) {
    HitOut miss;
    miss.t = INFINITY; miss.u = 0.0f; miss.v = 0.0f; miss.triangle = HIT_NONE;
    hits[slot] = miss;
    traversal[slot] = (uint4)(TRAVERSAL_DONE, 0u, 0u, 0u);
    return;
  }
  KdStackEntry stack[PTH_MAX_LEVELS];
  int sp = 0;
  uint node = 0u;
  uint bits = pth_walk(subtree, subtree_nodes, c.pth_levels, org, dir, inv_dir, &node, &t0, &t1, stack, &sp);
  traversal[slot] = (uint4)(node, as_uint(t0), as_uint(t1), (uint)sp);
  for (int k = 0; k < sp; ++k)
    traversal_stack[(uint)k * stack_stride + slot] = (float4)(as_float(stack[k].node), stack[k].tmin, stack[k].tmax, 0.0f);
  keys[i] = coherence_code(&c, origin_bounds, org, dir, bits);
}

/* Continues each ray's traversal in sorted order from the state pth_walk_and_code saved. */
__kernel void pth_resume(SCENE_KERNEL_PARAMS, __global const float4* path_org, __global const float4* path_dir,
                         __global const uint* sorted_slots, uint count, __global const uint4* traversal,
                         __global const float4* traversal_stack, uint stack_stride, __global HitOut* hits,
                         __global uint* steps) {
  uint i = get_global_id(0);
  if (i >= count) return;
  uint slot = sorted_slots[i];
  uint4 state = traversal[slot];
  uint visited = 0u;
  if (state.x != TRAVERSAL_DONE) {
    RenderParams p = *params;
    SceneView s = SCENE_VIEW(p);
    KdStackEntry stack[KD_MAX_DEPTH];
    for (uint k = 0u; k < state.w; ++k) {
      float4 e = traversal_stack[k * stack_stride + slot];
      stack[k].node = as_uint(e.x);
      stack[k].tmin = e.y;
      stack[k].tmax = e.z;
    }
    hits[slot] = kd_resume(&s.tree, v3_from4(path_org[slot]), v3_from4(path_dir[slot]), 0.0f, INFINITY, 0, state.x,
                           as_float(state.y), as_float(state.z), stack, (int)state.w, &visited);
  }
  steps[i] = visited;
}

#include "common/kdtree_speculative.h"

/* pth_resume with speculative traversal (--speculative): the same hits, bit for bit, with leaf
 * tests postponed until the work-group agrees. Launched with one SIMD group (32) per work-group;
 * every work item runs the group loop, so the items past `count` join as finished rays. */
__kernel void pth_resume_speculative(SCENE_KERNEL_PARAMS, __global const float4* path_org,
                                     __global const float4* path_dir, __global const uint* sorted_slots, uint count,
                                     __global const uint4* traversal, __global const float4* traversal_stack,
                                     uint stack_stride, __global HitOut* hits, __global uint* steps) {
  __local uint votes[3];
  uint i = get_global_id(0);
  uint slot = i < count ? sorted_slots[i] : 0u;
  uint4 state = i < count ? traversal[slot] : (uint4)(TRAVERSAL_DONE, 0u, 0u, 0u);
  int active = state.x != TRAVERSAL_DONE;
  RenderParams p = *params;
  SceneView s = SCENE_VIEW(p);
  KdStackEntry stack[KD_MAX_DEPTH];
  for (uint k = 0u; active && k < state.w; ++k) {
    float4 e = traversal_stack[k * stack_stride + slot];
    stack[k].node = as_uint(e.x);
    stack[k].tmin = e.y;
    stack[k].tmax = e.z;
  }
  KdSpeculativeRay ray;
  kd_spec_start(&ray, active, active ? v3_from4(path_org[slot]) : v3(0.0f, 0.0f, 1.0f),
                active ? v3_from4(path_dir[slot]) : v3(0.0f, 0.0f, 1.0f), 0.0f, INFINITY, state.x,
                as_float(state.y), as_float(state.z), (int)state.w);
  kd_spec_run_group(&s.tree, &ray, stack, votes);
  if (i >= count) return;
  if (active) hits[slot] = ray.hit;
  steps[i] = ray.visited;
}
