/* The partial traversal heuristic pipeline (Wang & Deng, Figure 3) between regeneration and
 * shading, on the tree the program is built for (the 4-wide BVH with COHORT_ACCEL_BVH4, else the
 * KD-tree): every live ray walks the top subtree in local memory and gets its coherence code;
 * the host sorts (code, slot) pairs on the device (32-bit codes where the layout fits);
 * pth_resume then continues each traversal in sorted order from the state the walk left, so no
 * node is visited twice and the hit equals a full traversal's. With 0 levels the walk is empty
 * and this is the hash sort of Garanzha & Loop (method `hash`). */
#ifndef COHORT_PTH_KERNELS_H
#define COHORT_PTH_KERNELS_H

#include "common/wavefront/wavefront_path.h"
#include "common/pth/coherence.h"
#if defined(COHORT_ACCEL_BVH4)
#include "common/accel/bvh4_path.h"
#endif
#if defined(COHORT_ACCEL_BVH8) || defined(COHORT_ACCEL_BVH8F)
#error "the pth and hash kernels walk the KD-tree or the 4-wide BVH; the host refuses them with --tree bvh8 and bvh8f"
#endif

/* A ray that is not traced (or misses the scene) this bounce: the largest key, so that it sorts
 * last, and no state for pth_resume. */
CO_INLINE uint64_t pth_skip(CO_GLOBAL TraversalState* traversal, uint32_t slot, uint64_t last) {
  traversal[slot] = traversal_done();
  return last;
}

CO_INLINE void pth_miss(CO_GLOBAL HitOut* hits, uint32_t slot) {
  hits[slot] = hit_none(INFINITY);
}

/* The walk of launch index i (< count): saves where the traversal stopped and returns the ray's
 * coherence code; rays that are not traced this bounce get the largest key, so they sort last and
 * pth_resume skips them. The KD-tree's walk (pth_walk) saves the cell and the stacked cells; the
 * BVH's (bvh4_walk) the node or leaf to go on with, its entry distance, and the pushed children. */
CO_INLINE uint64_t pth_walk_item(CO_PARAMS(PTH_WALK_PARAMS), const CO_LOCAL PTH_TOP_NODE* subtree, uint32_t i) {
  uint32_t slot = slot_of(i, queue, use_queue);
  CodeParams c = *code_params;
  uint64_t last = c.key_bits >= 64u ? ~(uint64_t)0 : (((uint64_t)1 << c.key_bits) - (uint64_t)1);
  values[i] = slot;
  if (path_item[slot] == ITEM_NONE || path_status[slot] != PATH_ALIVE) return pth_skip(traversal, slot, last);
  RenderParams p = *params;
  co_vec3 org = v3_from4(path_org[slot]), dir = v3_from4(path_dir[slot]);
  co_vec3 inv_dir = kd_inverse(dir);
  float t0 = 0.0f, t1 = INFINITY;
  /* the scene box: where a camera ray leaves it, for the end part's estimate */
  KdTreeView box = make_tree_view(nodes, leaf_triangles, triangles, p.scene_min, p.scene_max);
#if defined(COHORT_ACCEL_BVH4)
  /* on the BVH the walk tells a miss itself: the box is only needed for the end part */
  int inside = c.end_bits != 0u && kd_begin(&box, org, inv_dir, 0.0f, INFINITY, &t0, &t1);
#else
  int inside = kd_begin(&box, org, inv_dir, 0.0f, INFINITY, &t0, &t1);
#endif
  /* the previous hit is still in `hits` until this bounce's is written */
  float end_t = c.end_bits && inside ? estimated_end(path_segment[slot], hits[slot].t, t1) : 0.0f;
  TraversalState state;
  uint32_t bits;
  int sp = 0;
#if defined(COHORT_ACCEL_BVH4)
  /* the walk itself tells a miss: the BVH's boxes, not the scene box, decide what the full
   * traversal would visit */
  Bvh4View bvh = make_bvh4_view(nodes, leaf_triangles);
  Bvh4Ray r = bvh4_ray(org, dir CO_ALPHA_ARG(0u)); /* the walk tests no triangle: no alpha seed */
  uint32_t stack_ref[BVH4_STACK];
  float stack_t[BVH4_STACK];
  uint32_t ref;
  float ref_t;
  bits = bvh4_walk(subtree, subtree_nodes, c.pth_levels, &bvh, &r, 0.0f, INFINITY, &ref, &ref_t, stack_ref, stack_t,
                   &sp);
  if (ref == TRAVERSAL_DONE) {
    pth_miss(hits, slot);
    return pth_skip(traversal, slot, last);
  }
  state.node = ref;
  state.tmin = ref_t;
  state.tmax = 0.0f;
  for (int k = 0; k < sp; ++k) {
    SavedStackEntry e;
    e.node = stack_ref[k];
    e.tmin = stack_t[k];
    e.tmax = 0.0f;
    e.pad = 0u;
    traversal_stack[(uint32_t)k * stack_stride + slot] = e;
  }
#else
  if (!inside) {
    pth_miss(hits, slot);
    return pth_skip(traversal, slot, last);
  }
  KdStackEntry stack[PTH_MAX_LEVELS];
  uint32_t node = 0u;
  bits = pth_walk(subtree, subtree_nodes, c.pth_levels, org, dir, inv_dir, &node, &t0, &t1, stack, &sp);
  state.node = node;
  state.tmin = t0;
  state.tmax = t1;
  for (int k = 0; k < sp; ++k) {
    SavedStackEntry e;
    e.node = stack[k].node;
    e.tmin = stack[k].tmin;
    e.tmax = stack[k].tmax;
    e.pad = 0u;
    traversal_stack[(uint32_t)k * stack_stride + slot] = e;
  }
#endif
  state.depth = (uint32_t)sp;
  traversal[slot] = state;
  return coherence_code(&c, origin_bounds, org, dir, bits, end_t);
}

/* One copy of the subtree per work-group, before any work item may leave. */
#define PTH_LOAD_SUBTREE()                                                                         \
  CO_LOCAL_BIND(PTH_TOP_NODE, subtree)                                                             \
  for (uint32_t k = co_local_id(); k < subtree_nodes; k += co_local_size())                        \
    subtree[k] = ((const CO_GLOBAL PTH_TOP_NODE*)nodes)[k];                                        \
  co_barrier();

/* Keys of more than 32 bits (the paper's layout). */
CO_KERNEL pth_walk_and_code(CO_PARAMS(PTH_WALK_AND_CODE_PARAMS)) {
  PTH_LOAD_SUBTREE()
  uint32_t i = co_global_id();
  if (i < launch_count(count, counters, use_queue)) keys[i] = pth_walk_item(CO_ARGS(PTH_WALK_PARAMS), subtree, i);
}

/* Keys of at most 32 bits: half the sort's memory traffic and passes. */
CO_KERNEL pth_walk_and_code32(CO_PARAMS(PTH_WALK_AND_CODE32_PARAMS)) {
  PTH_LOAD_SUBTREE()
  uint32_t i = co_global_id();
  if (i < launch_count(count, counters, use_queue))
    keys[i] = (uint32_t)pth_walk_item(CO_ARGS(PTH_WALK_PARAMS), subtree, i);
}

#if !defined(COHORT_ACCEL_BVH4)
/* The `depth` stack entries pth_walk_and_code saved for `slot` (entry k of every slot together). */
CO_INLINE void load_traversal_stack(CO_GLOBAL const SavedStackEntry* traversal_stack, uint32_t stack_stride,
                                    uint32_t slot, uint32_t depth, KdStackEntry* stack) {
  for (uint32_t k = 0u; k < depth; ++k) {
    SavedStackEntry e = traversal_stack[k * stack_stride + slot];
    stack[k].node = e.node;
    stack[k].tmin = e.tmin;
    stack[k].tmax = e.tmax;
  }
}
#endif

/* Copies each sorted ray's origin, direction and saved traversal state (with its stack) to its
 * sorted position (--sort-payload gather), so that the resumed traversal reads them contiguously
 * instead of through the permutation. */
CO_KERNEL pth_gather(CO_PARAMS(PTH_GATHER_PARAMS)) {
  uint32_t i = co_global_id();
  if (i >= launch_count(count, counters, use_queue)) return;
  uint32_t slot = sorted_slots[i];
  TraversalState state = traversal[slot];
  sorted_traversal[i] = state;
  if (state.node == TRAVERSAL_DONE) return;
  sorted_org[i] = path_org[slot];
  sorted_dir[i] = path_dir[slot];
  for (uint32_t k = 0u; k < state.depth; ++k) sorted_stack[k * stack_stride + i] = traversal_stack[k * stack_stride + slot];
}

/* Where the resume reads sorted item i's ray and state: at i once pth_gather moved them there,
 * else at the item's slot. Hits always go to the slot, where shading reads them. */
CO_INLINE uint32_t resume_source(uint32_t i, uint32_t slot, uint32_t gathered) { return gathered ? i : slot; }

/* Continues each ray's traversal in sorted order from the state pth_walk_and_code saved. */
CO_KERNEL pth_resume(CO_PARAMS(PTH_RESUME_PARAMS)) {
  uint32_t i = co_global_id();
  if (i >= launch_count(count, counters, use_queue)) return;
  uint32_t slot = sorted_slots[i];
  uint32_t from = resume_source(i, slot, gathered);
  TraversalState state = traversal[from];
  uint32_t visited = 0u;
  if (state.node != TRAVERSAL_DONE) {
    RenderParams p = *params;
    SceneView s = SCENE_VIEW(p);
    co_vec3 org = v3_from4(path_org[from]), dir = v3_from4(path_dir[from]);
#if defined(COHORT_ACCEL_BVH4)
    uint32_t stack_ref[BVH4_STACK];
    float stack_t[BVH4_STACK];
    for (uint32_t k = 0u; k < state.depth; ++k) {
      SavedStackEntry e = traversal_stack[k * stack_stride + from];
      stack_ref[k] = e.node;
      stack_t[k] = e.tmin;
    }
    /* with COHORT_FEATURE_ALPHA the origin's w is the ray's alpha seed (PATH_SLOT, core/path_slot.h) */
    Bvh4Ray r = bvh4_ray(org, dir CO_ALPHA_ARG(alpha_seed_from_float(path_org[from].w)));
    HitOut hit = hit_none(INFINITY);
    bvh4_continue(&s.tree, &r, 0.0f, 0, &hit, state.node, state.tmin, stack_ref, stack_t, (int)state.depth, &visited);
    hits[slot] = hit;
#else
    KdStackEntry stack[KD_MAX_DEPTH];
    load_traversal_stack(traversal_stack, stack_stride, from, state.depth, stack);
    /* with COHORT_FEATURE_ALPHA the origin's w is the ray's alpha seed (PATH_SLOT, core/path_slot.h) */
    hits[slot] = kd_resume(&s.tree, org, dir, 0.0f, INFINITY, 0, state.node, state.tmin, state.tmax, stack,
                           (int)state.depth, &visited CO_ALPHA_ARG(alpha_seed_from_float(path_org[from].w)));
#endif
  }
  steps[i] = visited;
}

#if !defined(COHORT_ACCEL_BVH4)
#include "common/pth/kdtree_speculative.h"

/* pth_resume with speculative traversal (--speculative): the same hits, bit for bit, with leaf
 * tests postponed until the group agrees. Launched with one SIMD group (32) per work-group; every
 * work item runs the group loop, so the items past `count` join as finished rays. */
CO_KERNEL pth_resume_speculative(CO_PARAMS(PTH_RESUME_PARAMS)) {
  CO_SHARED uint32_t votes[3];
  count = launch_count(count, counters, use_queue);
  uint32_t i = co_global_id();
  uint32_t slot = i < count ? sorted_slots[i] : 0u;
  uint32_t from = resume_source(i, slot, gathered);
  TraversalState state = i < count ? traversal[from] : traversal_done();
  int active = state.node != TRAVERSAL_DONE;
  RenderParams p = *params;
  SceneView s = SCENE_VIEW(p);
  KdStackEntry stack[KD_MAX_DEPTH];
  if (active) load_traversal_stack(traversal_stack, stack_stride, from, state.depth, stack);
  KdSpeculativeRay ray;
  kd_spec_start(&ray, active, active ? v3_from4(path_org[from]) : v3(0.0f, 0.0f, 1.0f),
                active ? v3_from4(path_dir[from]) : v3(0.0f, 0.0f, 1.0f), 0.0f, INFINITY, state.node,
                state.tmin, state.tmax,
                (int)state.depth CO_ALPHA_ARG(active ? alpha_seed_from_float(path_org[from].w) : 0u));
  if (active) ray.unordered = kd_stack_unordered(stack, (int)state.depth);
  kd_spec_run_group(&s.tree, &ray, stack, votes);
  if (i >= count) return;
  if (active) hits[slot] = ray.hit;
  steps[i] = ray.visited;
}

#endif /* !COHORT_ACCEL_BVH4: speculation is the KD-tree walk's */

#endif
