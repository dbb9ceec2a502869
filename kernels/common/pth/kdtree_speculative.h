/* Speculative traversal (Aila & Laine 2009, "Understanding the efficiency of ray traversal on
 * GPUs"; Aila, Laine & Karras 2012): a ray that reaches a leaf postpones it and keeps walking the
 * tree until every ray of its group has found a leaf too; then the whole group tests leaves
 * together. Lanes spend fewer steps idle while neighbours run a different kind of work.
 *
 * Leaves are still tested in the order, and with the termination checks, of kd_resume: a ray
 * holds at most one postponed leaf and waits at the next one, a pending leaf is tested only if
 * the closest hit so far does not lie before its cell, and a cell found beyond the current hit
 * ends the walk exactly where kd_resume would stop. So the hit is bit for bit kd_resume's; only
 * the inner-node steps taken ahead of time (and counted in `visited`) differ.
 *
 * The group vote: a warp vote in CUDA, a sub-group `any` where an OpenCL device offers
 * cl_khr_subgroups; otherwise the whole work-group votes through three words of __local memory, one
 * barrier per step, in control flow that every work item of the group follows (docs/decisions.md: never
 * a barrier in divergent code). */
#ifndef COHORT_KDTREE_SPECULATIVE_H
#define COHORT_KDTREE_SPECULATIVE_H

#include "common/accel/kdtree_traverse.h"

typedef struct KdSpeculativeRay {
  co_vec3 org, dir, inv_dir;
  WatertightRay wr;
  float tmin;
  uint32_t node;       /* the cell the walk stands at, when walking */
  float t0, t1;
  uint32_t leaf;       /* the postponed leaf, when has_leaf */
  float leaf_t0;
  int walking;         /* node is a cell still to visit */
  int has_leaf;
  int waiting;         /* node is a second leaf: the walk waits for the group's leaf phase */
  int done;
  int sp;
  int unordered;       /* the stack holds a KD_STACK_UNORDERED entry: a cell beyond the hit is skipped, not the end */
  uint32_t visited;
  HitOut hit;
} KdSpeculativeRay;

/* Vote bits: some ray still looks for its leaf; some ray is not done. */
#define KD_VOTE_SEARCHING 1u
#define KD_VOTE_ACTIVE 2u

CO_INLINE uint32_t kd_spec_vote_bits(const KdSpeculativeRay* r) {
  if (r->done) return 0u;
  return KD_VOTE_ACTIVE | ((r->walking && !r->has_leaf) ? KD_VOTE_SEARCHING : 0u);
}

/* One step of the walk: visit an inner node, or postpone the leaf found. */
CO_INLINE void kd_spec_walk_step(const KdTreeView* tree, KdSpeculativeRay* r, KdStackEntry* stack) {
  if (r->done || !r->walking || r->waiting) return;
  if (kd_beyond_hit(r->hit.t, r->t0)) {  /* as kd_resume; a pending leaf, in front, is still tested */
    if (!r->unordered || r->sp == 0) {
      r->walking = 0;
      r->sp = 0;
      if (!r->has_leaf) r->done = 1;
    } else {
      kd_pop(stack, &r->sp, &r->node, &r->t0, &r->t1);
    }
    return;
  }
  KdNode node = tree->nodes[r->node];
  if (!kd_is_leaf(node)) {
    ++r->visited;
    kd_inner_step(node, r->org, r->dir, r->inv_dir, &r->node, &r->t0, &r->t1, stack, &r->sp, &r->unordered);
    return;
  }
  if (r->has_leaf) {
    r->waiting = 1;
    return;
  }
  ++r->visited;
  r->leaf = r->node;
  r->leaf_t0 = r->t0;
  r->has_leaf = 1;
  if (r->sp == 0) {
    r->walking = 0;
  } else {
    kd_pop(stack, &r->sp, &r->node, &r->t0, &r->t1);
  }
}

/* The group's leaf phase: test the postponed leaf, with kd_resume's termination check (with an
 * unordered stack, a leaf beyond the hit is skipped and the walk goes on, as kd_resume's does). */
CO_INLINE void kd_spec_leaf_phase(const KdTreeView* tree, KdSpeculativeRay* r) {
  if (r->done) return;
  if (r->has_leaf) {
    if (kd_beyond_hit(r->hit.t, r->leaf_t0)) {
      if (!r->unordered) {
        r->done = 1;
        return;
      }
    } else {
      kd_intersect_leaf(tree, tree->nodes[r->leaf], &r->wr, r->tmin, &r->hit, 0);
    }
    r->has_leaf = 0;
    r->waiting = 0;
  }
  if (!r->walking) r->done = 1;
}

CO_INLINE void kd_spec_start(KdSpeculativeRay* r, int active, co_vec3 org, co_vec3 dir, float tmin, float tmax,
                             uint32_t node, float t0, float t1, int sp CO_ALPHA_PARAM) {
  r->org = org; r->dir = dir; r->inv_dir = kd_inverse(dir);
  r->wr = watertight_ray(org, dir);
#if defined(COHORT_FEATURE_ALPHA)
  r->wr.alpha = 0; /* kd_spec_run_group points it at its tree's */
  r->wr.alpha_seed = alpha_seed;
#endif
  r->tmin = tmin;
  r->node = node; r->t0 = t0; r->t1 = t1;
  r->leaf = 0u; r->leaf_t0 = 0.0f;
  r->walking = active; r->has_leaf = 0; r->waiting = 0; r->done = !active;
  r->sp = sp;
  r->unordered = 0;  /* a restored stack: the caller sets it (kd_stack_unordered) */
  r->visited = 0u;
  r->hit = hit_none(tmax);
}

#if defined(__OPENCL_VERSION__) && defined(cl_khr_subgroups)
#pragma OPENCL EXTENSION cl_khr_subgroups : enable
#endif

/* OR of every work item's bits over the group (see the header comment). CUDA votes per warp with
 * __any_sync, OpenCL per sub-group where the device has them, else per work-group through `votes`:
 * 3 words, words 0 and 1 zero before step 0; word k % 3 collects step k, and word (k + 2) % 3 is
 * cleared after step k's barrier: its last readers (step k - 1) have all passed that barrier, and
 * its next writers (step k + 2) come after the next one. The host runs one work item per group. */
CO_INLINE uint32_t kd_group_vote(CO_LOCAL uint32_t* votes, uint32_t step, uint32_t bits) {
#if defined(__CUDACC__)
  (void)votes; (void)step;
  return (__any_sync(0xffffffffu, (int)(bits & KD_VOTE_SEARCHING)) ? KD_VOTE_SEARCHING : 0u) |
         (__any_sync(0xffffffffu, (int)(bits & KD_VOTE_ACTIVE)) ? KD_VOTE_ACTIVE : 0u);
#elif defined(__OPENCL_VERSION__) && defined(cl_khr_subgroups)
  (void)votes; (void)step;
  return (sub_group_any((int)(bits & KD_VOTE_SEARCHING)) ? KD_VOTE_SEARCHING : 0u) |
         (sub_group_any((int)(bits & KD_VOTE_ACTIVE)) ? KD_VOTE_ACTIVE : 0u);
#elif defined(__OPENCL_VERSION__)
  if (bits) atomic_or(&votes[step % 3u], bits);
  co_barrier();
  uint32_t all = votes[step % 3u];
  if (co_local_id() == 0u) votes[(step + 2u) % 3u] = 0u;
  return all;
#else
  (void)votes; (void)step;
  return bits;
#endif
}

CO_INLINE void kd_group_vote_init(CO_LOCAL uint32_t* votes) {
  if (co_local_id() < 3u) votes[co_local_id()] = 0u;
  co_barrier();
}

/* Runs every ray of the work group to its closest hit. Called by every work item of the group
 * (inactive ones too), never from divergent code. */
CO_INLINE void kd_spec_run_group(const KdTreeView* tree, KdSpeculativeRay* r, KdStackEntry* stack,
                                 CO_LOCAL uint32_t* votes) {
#if defined(COHORT_FEATURE_ALPHA)
  r->wr.alpha = &tree->alpha;
#endif
  kd_group_vote_init(votes);
  for (uint32_t step = 0u;; ++step) {
    uint32_t group = kd_group_vote(votes, step, kd_spec_vote_bits(r));
    if (!(group & KD_VOTE_ACTIVE)) break;
    if (group & KD_VOTE_SEARCHING)
      kd_spec_walk_step(tree, r, stack);
    else
      kd_spec_leaf_phase(tree, r);
  }
}

#endif
