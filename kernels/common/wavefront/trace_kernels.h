/* Traversal only: closest or any hit for a buffer of rays. Used by tests and the ray benchmarks.
 * The rays carry no material, so these kernels trace every triangle as opaque whatever the build
 * defines (the CUDA build compiles every feature into every file; the host never gives the trace
 * program a scene's features). */
#ifndef COHORT_TRACE_KERNELS_H
#define COHORT_TRACE_KERNELS_H

#if defined(COHORT_FEATURE_ALPHA) && defined(COHORT_INTERSECT_H)
#error "trace_kernels.h traces without alpha: include it before any other kernel header, or without COHORT_FEATURE_ALPHA"
#endif
#undef COHORT_FEATURE_ALPHA

#include "common/core/kernel_params.h"
#include "common/accel/scene_accel.h"

CO_KERNEL trace_rays(CO_PARAMS(TRACE_RAYS_PARAMS)) {
  uint32_t i = co_global_id();
  if (i >= count) return;
  SceneAccel tree = make_scene_accel(nodes, leaf_triangles, triangles, scene_min, scene_max);
#if defined(COHORT_ACCEL_BVH8F) && defined(COHORT_PAIRED_WALKS)
  /* paired walks (bvh8f_trace_pair; a CPU's option): an even item traces its ray and the next in
   * turn, an odd one returns, which on a CPU costs a branch */
  if (i & 1u) return;
  if (i + 1u < count) {
    RayIn ra = rays[i], rb = rays[i + 1u];
    Bvh8fWalk a, b;
    bvh8f_walk_start(&tree, &a, v3_from4(ra.origin), v3_from4(ra.dir), ra.origin.w, ra.dir.w, (int)any_hit);
    bvh8f_walk_start(&tree, &b, v3_from4(rb.origin), v3_from4(rb.dir), rb.origin.w, rb.dir.w, (int)any_hit);
    bvh8f_trace_pair(&tree, &a, &b);
    hits[i] = a.hit;
    hits[i + 1u] = b.hit;
    return;
  }
#endif
  RayIn r = rays[i];
  hits[i] = scene_trace_steps(&tree, v3_from4(r.origin), v3_from4(r.dir), r.origin.w, r.dir.w, (int)any_hit, 0);
}

/* trace_rays with the nodes each ray visited: the straggler tests. */
CO_KERNEL trace_rays_steps(CO_PARAMS(TRACE_RAYS_STEPS_PARAMS)) {
  uint32_t i = co_global_id();
  if (i >= count) return;
  SceneAccel tree = make_scene_accel(nodes, leaf_triangles, triangles, scene_min, scene_max);
  RayIn r = rays[i];
  uint32_t visited = 0u;
  hits[i] = scene_trace_steps(&tree, v3_from4(r.origin), v3_from4(r.dir), r.origin.w, r.dir.w, (int)any_hit, &visited);
  steps[i] = visited;
}

/* The rest walks the KD-tree itself (partial traversal, resume, speculation). */
#if !defined(COHORT_ACCEL_BVH4) && !defined(COHORT_ACCEL_BVH8) && !defined(COHORT_ACCEL_BVH8F)
#include "common/pth/coherence.h"

/* Partial traversal of the top `levels` (subtree in local memory) then resumed traversal, for a
 * buffer of rays: the test that PTH + resume finds exactly the hit of kd_trace, and that the PTH
 * bits match a reference walk. */
CO_KERNEL trace_rays_pth(CO_PARAMS(TRACE_RAYS_PTH_PARAMS)) {
  CO_LOCAL_BIND(KdNode, subtree)
  for (uint32_t k = co_local_id(); k < subtree_nodes; k += co_local_size()) subtree[k] = nodes[k];
  co_barrier();
  uint32_t i = co_global_id();
  if (i >= count) return;
  KdTreeView tree = make_tree_view(nodes, leaf_triangles, triangles, scene_min, scene_max);
  RayIn r = rays[i];
  co_vec3 org = v3_from4(r.origin), dir = v3_from4(r.dir);
  co_vec3 inv_dir = kd_inverse(dir);
  float t0, t1;
  HitOut hit = hit_none(r.dir.w);
  uint32_t bits = 0u;
  if (kd_begin(&tree, org, inv_dir, r.origin.w, r.dir.w, &t0, &t1)) {
    KdStackEntry stack[KD_MAX_DEPTH];
    int sp = 0;
    uint32_t node = 0u;
    bits = pth_walk(subtree, subtree_nodes, levels, org, dir, inv_dir, &node, &t0, &t1, stack, &sp);
    hit = kd_resume(&tree, org, dir, r.origin.w, r.dir.w, 0, node, t0, t1, stack, sp, 0);
  }
  hits[i] = hit;
  pth_bits[i] = bits;
}

#include "common/pth/kdtree_speculative.h"

/* kd_trace with speculative traversal, for a buffer of rays: the test that it finds exactly the
 * hit of kd_trace. Every work item runs the group loop; items past `count` join as finished. */
CO_KERNEL trace_rays_speculative(CO_PARAMS(TRACE_RAYS_SPECULATIVE_PARAMS)) {
  CO_SHARED uint32_t votes[3];
  uint32_t i = co_global_id();
  KdTreeView tree = make_tree_view(nodes, leaf_triangles, triangles, scene_min, scene_max);
  RayIn r = i < count ? rays[i] : rays[0];
  co_vec3 org = v3_from4(r.origin), dir = v3_from4(r.dir);
  float t0 = 0.0f, t1 = 0.0f;
  int active = i < count && kd_begin(&tree, org, kd_inverse(dir), r.origin.w, r.dir.w, &t0, &t1);
  KdStackEntry stack[KD_MAX_DEPTH];
  KdSpeculativeRay ray;
  kd_spec_start(&ray, active, org, dir, r.origin.w, r.dir.w, 0u, t0, t1, 0);
  kd_spec_run_group(&tree, &ray, stack, votes);
  if (i >= count) return;
  hits[i] = ray.hit;
  steps[i] = ray.visited;
}

#endif /* neither BVH */

#endif
