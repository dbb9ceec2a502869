/* Front-to-back stack traversal of the KD-tree (Havran's thesis, "Heuristic Ray Shooting
 * Algorithms", 2000, algorithm TA_B^rec as in pbrt): visit the near child first, push the far one
 * with its t interval, and stop as soon as the closest hit lies before the next cell. */
#ifndef COHORT_KDTREE_TRAVERSE_H
#define COHORT_KDTREE_TRAVERSE_H

#include "common/accel/intersect.h"

/* The builder caps depth at KD_MAX_DEPTH, so the stack never overflows. */
#define KD_MAX_DEPTH 48

typedef struct KdTreeView {
  const CO_GLOBAL KdNode* nodes;
  const CO_GLOBAL uint32_t* leaf_triangles;
  const CO_GLOBAL Triangle* triangles;
  co_vec3 lo, hi;
#if defined(COHORT_FEATURE_ALPHA)
  AlphaView alpha; /* set by make_scene_view */
#endif
} KdTreeView;

CO_INLINE KdTreeView make_tree_view(const CO_GLOBAL KdNode* nodes, const CO_GLOBAL uint32_t* leaf_triangles,
                                    const CO_GLOBAL Triangle* triangles, co_float4 lo, co_float4 hi) {
  KdTreeView t;
  t.nodes = nodes;
  t.leaf_triangles = leaf_triangles;
  t.triangles = triangles;
  t.lo = v3_from4(lo);
  t.hi = v3_from4(hi);
  return t;
}

typedef struct KdStackEntry {
  uint32_t node;  /* with KD_STACK_UNORDERED where kd_inner_step pushed it for a ray lying in the plane */
  float tmin, tmax;
} KdStackEntry;

/* Entries are pushed front to back: a deeper entry never starts before one above it, so a walk that
 * pops a cell beyond its closest hit can stop there. A ray lying in a split plane breaks that order:
 * kd_inner_step pushes the far side with the cell's whole interval and marks the entry with this bit
 * of the node index (nodes stay below 2^31); a walk whose stack holds such an entry goes on through
 * the stack instead of stopping (kd_resume). The bit is stripped on every pop. */
#define KD_STACK_UNORDERED 0x80000000u

/* Pops the top entry into the walk's cell, without the KD_STACK_UNORDERED mark. */
CO_INLINE void kd_pop(const KdStackEntry* stack, int* sp, uint32_t* node, float* t0, float* t1) {
  *sp -= 1;
  *node = stack[*sp].node & ~KD_STACK_UNORDERED;
  *t0 = stack[*sp].tmin;
  *t1 = stack[*sp].tmax;
}

/* Whether any of the `sp` entries (a stack restored from a saved state) carries KD_STACK_UNORDERED. */
CO_INLINE int kd_stack_unordered(const KdStackEntry* stack, int sp) {
  uint32_t any = 0u;
  for (int k = 0; k < sp; ++k) any |= stack[k].node;
  return (any & KD_STACK_UNORDERED) != 0u;
}

/* The closest hit is the least (t, triangle index) over every triangle the ray meets, whatever the
 * tree: a tie in t goes to the lower index, and a cell is skipped only when it starts beyond the
 * best t by more than the few ulps by which kd_inner_step widens the cell intervals
 * (KD_TERMINATION_SLACK). So any tree over the same triangles (the deep or the compact one, a
 * shallower one under a memory budget) gives every ray the same hit bit for bit, where the first hit
 * found in front-to-back order would differ between trees at ties on shared edges and vertices
 * (docs/design.md, "The closest hit does not depend on the tree"). */
#define KD_TERMINATION_SLACK 1.00001f

/* True when a cell entered at t0 lies wholly beyond the closest hit so far, hit_t. */
CO_INLINE int kd_beyond_hit(float hit_t, float t0) { return hit_t * KD_TERMINATION_SLACK < t0; }

/* Takes triangle `tri`'s hit at (t, u, v), found in (tmin, any_hit ? hit->t : infinity), into *hit
 * where it is the least (t, index) so far; any_hit keeps the first hit and returns 1 there. Every
 * leaf test of every tree (consider_triangle; the 8-wide BVH with float planes' four-triangle
 * test, bvh8f_traverse.h) decides through it, so they all keep the same hits. */
CO_INLINE int record_hit(const WatertightRay* wr, uint32_t tri, float t, float u, float v, HitOut* hit, int any_hit) {
  /* closest hit: also t equal to the best, which then goes to the lower index; a ray's own
   * tmax (no triangle yet) stays exclusive */
  if (t < hit->t || (t == hit->t && tri < hit->triangle && hit->triangle != HIT_NONE)) {
#if defined(COHORT_FEATURE_ALPHA)
    /* a cut-out or passed-through hit (alpha.h) is as if the triangle were not there */
    if (alpha_skips(wr->alpha, wr->alpha_seed, tri, u, v)) return 0;
#else
    (void)wr;
#endif
    hit->t = t; hit->u = u; hit->v = v; hit->triangle = tri;
    if (any_hit) return 1;
  }
  return 0;
}

/* Tests triangle `tri` (at tp), narrowing *hit to the least (t, index); any_hit keeps the first hit
 * before hit->t and returns 1 there. The KD-tree's leaves and the BVHs' (bvh4_traverse.h) go
 * through it, so they find the same hits. */
CO_INLINE int consider_triangle(const WatertightRay* wr, CO_GLOBAL const Triangle* tp, uint32_t tri, float ray_tmin,
                                HitOut* hit, int any_hit) {
  float t, u, v;
  return intersect_triangle(wr, v3_from4(tp->v0), v3_from4(tp->v1), v3_from4(tp->v2), ray_tmin,
                            any_hit ? hit->t : INFINITY, &t, &u, &v) &&
         record_hit(wr, tri, t, u, v, hit, any_hit);
}

/* The `count` triangles listed from `first` in a leaf list, through consider_triangle. */
CO_INLINE int intersect_leaf_list(const CO_GLOBAL uint32_t* list, uint32_t first, uint32_t count,
                                  const CO_GLOBAL Triangle* triangles, const WatertightRay* wr, float ray_tmin,
                                  HitOut* hit, int any_hit) {
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t tri = list[first + i];
    if (consider_triangle(wr, &triangles[tri], tri, ray_tmin, hit, any_hit)) return 1;
  }
  return 0;
}

CO_INLINE int kd_intersect_leaf(const KdTreeView* tree, KdNode leaf, const WatertightRay* wr,
                                float ray_tmin, HitOut* hit, int any_hit) {
  return intersect_leaf_list(tree->leaf_triangles, kd_leaf_first(leaf), kd_leaf_count(leaf), tree->triangles, wr,
                             ray_tmin, hit, any_hit);
}

/* One step at an inner node: picks the next node and pushes the far child when the ray needs
 * both. Returns the step's partial-traversal bits (Wang & Deng, Figure 1): bit 1 is set when the
 * ray goes to the left child next, bit 0 when it pushes the other child. Sets *unordered when it
 * pushed an entry out of front-to-back order (KD_STACK_UNORDERED). Every traversal (full, partial in
 * local memory, resumed) takes its inner steps through this one function, so they all round the
 * same way and a resumed traversal finds exactly the hit of a full one. */
CO_INLINE uint32_t kd_inner_step(KdNode node, co_vec3 org, co_vec3 dir, co_vec3 inv_dir, uint32_t* node_index,
                                 float* t0, float* t1, KdStackEntry* stack, int* sp, int* unordered) {
  uint32_t axis = kd_axis(node);
  float split = co_as_float(node.word1);
  float o = v3_get(org, axis), d = v3_get(dir, axis);
  float t_plane = (split - o) * v3_get(inv_dir, axis);
  int below_first = (o < split) || (o == split && d <= 0.0f);
  uint32_t near_child = kd_left_child(node) + (below_first ? 0u : 1u);
  uint32_t far_child = kd_left_child(node) + (below_first ? 1u : 0u);
  /* The plane distance and the watertight hit distance round differently, so a hit on the
   * split plane can fall just outside the cell the plane bounds. Widening the decision and
   * both intervals by a few ulps keeps such hits (on shared edges and vertices that lie in
   * split planes) inside a visited cell. !(t_plane > 0) takes the near side alone when the plane
   * lies behind the origin, and catches an origin in the plane (t_plane +-0, or NaN for a ray lying
   * in it), handled below. The widening is relative to the plane distance, capped at twice the
   * cell's exit: past that cap the plane lies beyond the cell and every comparison below decides as
   * without it, but a ray parallel to the plane (direction component 0 or -0, t_plane infinite)
   * would otherwise get an infinite eps, push the far child with the whole interval at every split
   * on that axis and walk a large part of the tree (the straggler rays of docs/design.md). */
  float eps = 4e-6f * fmax(fmin(fabs(t_plane), 2.0f * fabs(*t1)), fabs(*t1));
  uint32_t next, pushed = 0u;
  if (t_plane > *t1 + eps || !(t_plane > 0.0f)) {
    next = near_child;
    if (o == split) {
      /* The origin lies in the plane, which may hold flat triangles stored on either side. The near
       * child is the side the ray goes into. A ray lying in the plane meets both sides over its
       * whole interval: the other one is pushed with it, out of front-to-back order. Otherwise the
       * other side is touched at the origin only: where the cell starts there, it is visited first
       * over [t0, eps] and the side the ray goes into is pushed with the whole interval. */
      if (d == 0.0f) {
        stack[*sp].node = far_child | KD_STACK_UNORDERED; stack[*sp].tmin = *t0; stack[*sp].tmax = *t1;
        *sp += 1;
        pushed = 1u;
        *unordered = 1;
      } else if (!(*t0 > eps)) {
        stack[*sp].node = near_child; stack[*sp].tmin = *t0; stack[*sp].tmax = *t1;
        *sp += 1;
        next = far_child;
        *t1 = fmin(*t1, eps);
        pushed = 1u;
      }
    }
  } else if (t_plane < *t0 - eps) {
    next = far_child;
  } else {
    stack[*sp].node = far_child; stack[*sp].tmin = fmax(*t0, t_plane - eps); stack[*sp].tmax = *t1;
    *sp += 1;
    next = near_child;
    *t1 = fmin(*t1, t_plane + eps);
    pushed = 1u;
  }
  *node_index = next;
  return ((next == kd_left_child(node)) ? 2u : 0u) | pushed;
}

/* Clips the ray to the tree's box; 0 when it misses. */
CO_INLINE int kd_begin(const KdTreeView* tree, co_vec3 org, co_vec3 inv_dir, float tmin, float tmax, float* t0,
                       float* t1) {
  *t0 = tmin;
  *t1 = tmax;
  return intersect_box(org, inv_dir, tree->lo, tree->hi, t0, t1);
}

CO_INLINE co_vec3 kd_inverse(co_vec3 dir) { return v3(1.0f / dir.x, 1.0f / dir.y, 1.0f / dir.z); }

/* Continues a traversal from `node_index` with cell interval [t0, t1] and `sp` stacked cells.
 * `steps`, when not null, counts nodes visited (the SIMD efficiency figure). */
CO_INLINE HitOut kd_resume(const KdTreeView* tree, co_vec3 org, co_vec3 dir, float tmin, float tmax, int any_hit,
                           uint32_t node_index, float t0, float t1, KdStackEntry* stack, int sp,
                           uint32_t* steps CO_ALPHA_PARAM) {
  HitOut hit = hit_none(tmax);
  co_vec3 inv_dir = kd_inverse(dir);
  WatertightRay wr = watertight_ray(org, dir);
#if defined(COHORT_FEATURE_ALPHA)
  wr.alpha = &tree->alpha;
  wr.alpha_seed = alpha_seed;
#endif
  uint32_t visited = 0u;
  int unordered = kd_stack_unordered(stack, sp);
  for (;;) {
    int beyond = 0;
    for (;;) {
      if (kd_beyond_hit(hit.t, t0)) {  /* the closest hit lies before this cell */
        beyond = 1;
        break;
      }
      KdNode node = tree->nodes[node_index];
      ++visited;
      if (!kd_is_leaf(node)) {
        kd_inner_step(node, org, dir, inv_dir, &node_index, &t0, &t1, stack, &sp, &unordered);
        continue;
      }
      if (kd_intersect_leaf(tree, node, &wr, tmin, &hit, any_hit)) break;
      if (sp == 0) break;
      kd_pop(stack, &sp, &node_index, &t0, &t1);
    }
    /* The cells stacked under one that starts beyond the hit start later still, unless an unordered
     * entry is among them (KD_STACK_UNORDERED): then the walk skips the cell and goes on through the
     * stack. Outside the walk's loop, so the walks of other rays are the same code as without it. */
    if (!beyond || !unordered || sp == 0) break;
    kd_pop(stack, &sp, &node_index, &t0, &t1);
  }
  if (steps) *steps = visited;
  return hit;
}

/* Closest hit (any_hit = 0) or any hit (any_hit = 1) in (tmin, tmax). A miss has triangle HIT_NONE.
 * `steps`, when not null, receives the number of nodes visited. With COHORT_FEATURE_ALPHA a last
 * argument is the ray's alpha seed (alpha.h). */
CO_INLINE HitOut kd_trace_steps(const KdTreeView* tree, co_vec3 org, co_vec3 dir, float tmin, float tmax, int any_hit,
                                uint32_t* steps CO_ALPHA_PARAM) {
  float t0, t1;
  if (!kd_begin(tree, org, kd_inverse(dir), tmin, tmax, &t0, &t1)) {
    if (steps) *steps = 0u;
    return hit_none(tmax);
  }
  KdStackEntry stack[KD_MAX_DEPTH];
  return kd_resume(tree, org, dir, tmin, tmax, any_hit, 0u, t0, t1, stack, 0, steps CO_ALPHA_ARG(alpha_seed));
}

#if !defined(COHORT_FEATURE_ALPHA)
CO_INLINE HitOut kd_trace(const KdTreeView* tree, co_vec3 org, co_vec3 dir, float tmin, float tmax, int any_hit) {
  return kd_trace_steps(tree, org, dir, tmin, tmax, any_hit, 0);
}
#endif

#endif
