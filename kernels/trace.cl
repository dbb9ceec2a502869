/* Traversal only: closest or any hit for a buffer of rays. Used by tests and the ray benchmarks. */
#include "common/kdtree_traverse.h"

__kernel void trace_rays(__global const KdNode* nodes, __global const uint* leaf_triangles,
                         __global const Triangle* triangles, float4 scene_min, float4 scene_max,
                         __global const RayIn* rays, __global HitOut* hits, uint count, uint any_hit) {
  uint i = get_global_id(0);
  if (i >= count) return;
  KdTreeView tree = make_tree_view(nodes, leaf_triangles, triangles, scene_min, scene_max);
  RayIn r = rays[i];
  hits[i] = kd_trace(&tree, v3_from4(r.origin), v3_from4(r.dir), r.origin.w, r.dir.w, (int)any_hit);
}

#include "common/coherence.h"

/* Partial traversal of the top `levels` (subtree in local memory) then resumed traversal, for a
 * buffer of rays: the test that PTH + resume finds exactly the hit of kd_trace, and that the PTH
 * bits match a reference walk. */
__kernel void trace_rays_pth(__global const KdNode* nodes, __global const uint* leaf_triangles,
                             __global const Triangle* triangles, float4 scene_min, float4 scene_max,
                             __global const RayIn* rays, __global HitOut* hits, uint count, __local KdNode* subtree,
                             uint subtree_nodes, uint levels, __global uint* pth_bits) {
  for (uint k = get_local_id(0); k < subtree_nodes; k += get_local_size(0)) subtree[k] = nodes[k];
  barrier(CLK_LOCAL_MEM_FENCE);
  uint i = get_global_id(0);
  if (i >= count) return;
  KdTreeView tree = make_tree_view(nodes, leaf_triangles, triangles, scene_min, scene_max);
  RayIn r = rays[i];
  co_vec3 org = v3_from4(r.origin), dir = v3_from4(r.dir);
  co_vec3 inv_dir = kd_inverse(dir);
  float t0, t1;
  HitOut hit;
  hit.t = r.dir.w; hit.u = 0.0f; hit.v = 0.0f; hit.triangle = HIT_NONE;
  uint bits = 0u;
  if (kd_begin(&tree, org, inv_dir, r.origin.w, r.dir.w, &t0, &t1)) {
    KdStackEntry stack[KD_MAX_DEPTH];
    int sp = 0;
    uint node = 0u;
    bits = pth_walk(subtree, subtree_nodes, levels, org, dir, inv_dir, &node, &t0, &t1, stack, &sp);
    hit = kd_resume(&tree, org, dir, r.origin.w, r.dir.w, 0, node, t0, t1, stack, sp, 0);
  }
  hits[i] = hit;
  pth_bits[i] = bits;
}

#include "common/kdtree_speculative.h"

/* kd_trace with speculative traversal, for a buffer of rays: the test that it finds exactly the
 * hit of kd_trace. Every work item runs the group loop; items past `count` join as finished. */
__kernel void trace_rays_speculative(__global const KdNode* nodes, __global const uint* leaf_triangles,
                                     __global const Triangle* triangles, float4 scene_min, float4 scene_max,
                                     __global const RayIn* rays, __global HitOut* hits, uint count,
                                     __global uint* steps) {
  __local uint votes[3];
  uint i = get_global_id(0);
  KdTreeView tree = make_tree_view(nodes, leaf_triangles, triangles, scene_min, scene_max);
  RayIn r = i < count ? rays[i] : rays[0];
  co_vec3 org = v3_from4(r.origin), dir = v3_from4(r.dir);
  float t0, t1;
  int active = i < count && kd_begin(&tree, org, kd_inverse(dir), r.origin.w, r.dir.w, &t0, &t1);
  KdStackEntry stack[KD_MAX_DEPTH];
  KdSpeculativeRay ray;
  kd_spec_start(&ray, active, org, dir, r.origin.w, r.dir.w, 0u, t0, t1, 0);
  kd_spec_run_group(&tree, &ray, stack, votes);
  if (i >= count) return;
  hits[i] = ray.hit;
  steps[i] = ray.visited;
}
