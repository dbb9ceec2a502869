/* Closest-hit and any-hit traversal of the 4-wide BVH (types.h, Bvh4Node): each step tests a
 * node's four child boxes at once, goes on with the nearest child the ray enters and pushes the
 * others, farthest first. It visits about a quarter of the nodes a KD-tree walk does and tests
 * fewer triangles: 1.5-2.3x the KD-tree's samples per CPU second on PoCL, 1.1-2.1x its rays/s on the
 * H200, 0.9x on one scene (2026-12-03, results/raw/pocl-2026-12-03-ee75f6e, nvidia-h200-2026-12-03-ff6bbc9).
 *
 * The hit is the one kd_trace finds, bit for bit: the same watertight test on the same kept
 * triangles, the least (t, triangle index) over every triangle the ray meets, and a box is
 * skipped only when it starts beyond the best t by more than KD_TERMINATION_SLACK. The box test
 * only has to be conservative, never exact: a box entered by mistake costs a visit, not a
 * different hit. So the builder pads every box by 2^-20 of the scene's largest coordinate (the
 * watertight test can report a hit on a shared edge for a ray that passes a few ulps outside the
 * triangle's exact box: 1,069 of 30,000 rays at the vertices of a coplanar grid without it), a zero
 * direction component becomes a tiny one (no 0 * inf NaN) and the exit distance is widened by a
 * few ulps, as in intersect_box. */
#ifndef COHORT_BVH4_TRAVERSE_H
#define COHORT_BVH4_TRAVERSE_H

#include "common/accel/kdtree_traverse.h"

/* Entries of the traversal stack: a step pushes at most three children, and the builder keeps
 * the tree at most BVH4_MAX_DEPTH levels deep. */
#define BVH4_MAX_DEPTH 64
#define BVH4_STACK (3 * BVH4_MAX_DEPTH)

/* The leaves hold their triangles themselves, in leaf order (a triangle split into several
 * references appears once per leaf), each with its kept-triangle index in v0.w: a leaf costs one
 * run of consecutive loads instead of a list entry and then a triangle elsewhere. With the
 * near-plane selection below (and 2 MiB pages on CPUs): Sponza interior diffuse rays 1.15-1.2x on
 * PoCL, 1.14-1.18x on the H200 (2026-12-03, results/raw/nvidia-h200-2026-12-03-79b7d2b). */
typedef struct Bvh4View {
  const CO_GLOBAL Bvh4Node* nodes;
  const CO_GLOBAL Triangle* leaf_triangles;
#if defined(COHORT_FEATURE_ALPHA)
  AlphaView alpha; /* set by make_scene_view */
#endif
} Bvh4View;

/* The scene's arrays as the kernels receive them: a BVH4 travels in the buffers of KD nodes and
 * leaf lists. */
CO_INLINE Bvh4View make_bvh4_view(const CO_GLOBAL KdNode* nodes, const CO_GLOBAL uint32_t* leaf_lists) {
  Bvh4View b;
  b.nodes = (const CO_GLOBAL Bvh4Node*)nodes;
  b.leaf_triangles = (const CO_GLOBAL Triangle*)leaf_lists;
  return b;
}

/* A leaf's triangles, as intersect_leaf_list; returns 1 when an any-hit query is answered. */
CO_INLINE int bvh4_intersect_leaf(const CO_GLOBAL Triangle* leaf, uint32_t count, const WatertightRay* wr,
                                  float ray_tmin, HitOut* hit, int any_hit) {
  for (uint32_t i = 0; i < count; ++i)
    if (consider_triangle(wr, &leaf[i], co_as_uint(leaf[i].v0.w), ray_tmin, hit, any_hit)) return 1;
  return 0;
}

/* 1 / d for the box tests, with |d| below 1e-18 taken as 1e-18 of its sign: the slabs stay finite
 * and a box is only ever entered more often than exactly. A NaN component is taken as 1e-18 too:
 * a NaN inverse made every slab NaN, which min and max drop, so the unused lanes of a node were
 * entered and the walk followed their invalid references out of the arrays; now the walk stays in
 * the tree and the triangle test, whose comparisons are false for NaN, reports no hit. */
CO_INLINE float bvh4_inverse(float d) {
  float tiny = d < 0.0f ? -1e-18f : 1e-18f;
  return 1.0f / (fabs(d) >= 1e-18f ? d : tiny);
}

/* Starts loading a pushed child's cache lines, for when it is popped: an inner node's two, or a
 * leaf's first and last line and, past two triangles, the second (a leaf of four that starts late
 * in a line spans a fourth, which is left to the hardware). On CPUs a walk is one chain of
 * dependent loads, and a node that misses the caches stalls it. Sponza interior on PoCL and Intel's runtime: 7-11 % fewer render
 * CPU seconds, the conference unchanged. Prefetching every child of each node as it is loaded
 * gained more on Sponza (11-15 %) but cost the conference, whose walk stays in the caches, 20 % on
 * PoCL (2026-12-03, results/raw/nvidia-h200-2026-12-03-1855911). A no-op where the host does not ask for it
 * (co_prefetch, port.h). */
CO_INLINE void bvh4_prefetch(const Bvh4View* bvh, uint32_t ref) {
  if (bvh4_is_leaf(ref)) {
    const CO_GLOBAL char* first = (const CO_GLOBAL char*)&bvh->leaf_triangles[bvh4_leaf_first(ref)];
    const CO_GLOBAL char* last = first + bvh4_leaf_count(ref) * sizeof(Triangle) - 1u;
    co_prefetch(first);
    if (bvh4_leaf_count(ref) > 2u) co_prefetch(first + 64);
    co_prefetch(last);
  } else {
    const CO_GLOBAL char* node = (const CO_GLOBAL char*)&bvh->nodes[ref];
    co_prefetch(node);
    co_prefetch(node + 64);
  }
}

/* Puts the pair with the smaller t first (a compare-exchange of the sorting network). */
#define BVH4_ORDER(ta, ra, tb, rb)                                  \
  do {                                                              \
    if ((tb) < (ta)) {                                              \
      float tt_ = (ta); (ta) = (tb); (tb) = tt_;                    \
      uint32_t rr_ = (ra); (ra) = (rb); (rb) = rr_;                 \
    }                                                               \
  } while (0)

/* What a walk keeps of its ray: the watertight set-up, the inverse direction and the slab offsets
 * (bvh_slab_offsets) splatted over four lanes, and the plane each slab is entered through, by the
 * direction's sign: lo ahead of hi for a positive component. With lo <= hi the entry plane's
 * distance is the smaller, so this picks what a min and a max of the two would; an unused lane
 * (lo = hi = +infinity) gives equal values either way. */
typedef struct Bvh4Ray {
  WatertightRay wr;
  co_float4 near_ox, near_oy, near_oz; /* the entry planes' offsets (bvh_slab_offsets) */
  co_float4 far_ox, far_oy, far_oz;    /* the exit planes' */
  co_float4 ix, iy, iz;
  int near_x, near_y, near_z;
} Bvh4Ray;

/* What every BVH ray splats over its lanes: the origin and the inverse direction (bvh4_inverse; the
 * inverses made beforehand: bvh_slab_ray_inverted, for set-ups that divide several rays at once). An
 * origin that is not finite hits nothing: it becomes -infinity with unit inverses, so every plane is
 * +infinity away and no box is entered (NaN slabs would enter every lane, the unused ones too, whose
 * references are no nodes). So does an origin whose product with the inverse overflows (a coordinate
 * beyond 1e20: |inverse| is at most 1e18), which the fused slabs (bvh_slab_offsets) cannot offset;
 * unfused or fused, every device gives such a ray the same answer. */
CO_INLINE void bvh_slab_ray_inverted(co_vec3 org, co_vec3 inv, co_vec3* origin, co_vec3* inverse) {
  if (v3_is_finite(org) && fabs(org.x * inv.x) <= 1e38f && fabs(org.y * inv.y) <= 1e38f &&
      fabs(org.z * inv.z) <= 1e38f) {
    *origin = org;
    *inverse = inv;
  } else {
    *origin = v3_splat(-INFINITY);
    *inverse = v3_splat(1.0f);
  }
}
CO_INLINE void bvh_slab_ray(co_vec3 org, co_vec3 dir, co_vec3* origin, co_vec3* inverse) {
  bvh_slab_ray_inverted(org, v3(bvh4_inverse(dir.x), bvh4_inverse(dir.y), bvh4_inverse(dir.z)), origin, inverse);
}

/* A slab's distance, fma(plane, inverse, offset) in one rounding where the device fuses (the host's
 * default), (plane - origin) * inverse in two where the host passes -DCOHORT_UNFUSED_SLABS (an
 * OpenCL GPU, whose compiler ran the fused walk slower; a device without a hardware fma; Oclgrind:
 * runtime/backend/device_support.cpp). Fused, the offset is -(origin * inverse), moved by 2^-21 of
 * itself so that the entry distance is never above and the exit never below the exact
 * (plane - origin) * inverse before the fma's one rounding (the product's rounding is at most 2^-24
 * of it): the boxes only grow, by about 2^-21 of the origin's coordinate, far below their padding,
 * so a box is entered more often than exactly, never less, and the hit does not change. Unfused,
 * both offsets are the origin. bvh_slab_ray's -infinity origin gives +infinity fused: every plane
 * +infinity away either way. */
#if defined(COHORT_UNFUSED_SLABS)
#define BVH_SLAB4(plane, inverse, offset) co_f4_mul(co_f4_sub((plane), (offset)), (inverse))
#define BVH_SLAB8(plane, inverse, offset) co_f8_mul(co_f8_sub((plane), (offset)), (inverse))
#else
#define BVH_SLAB4(plane, inverse, offset) co_f4_fma((plane), (inverse), (offset))
#define BVH_SLAB8(plane, inverse, offset) co_f8_fma((plane), (inverse), (offset))
#endif
CO_INLINE void bvh_slab_offsets(co_vec3 origin, co_vec3 inverse, co_vec3* near_offset, co_vec3* far_offset) {
#if defined(COHORT_UNFUSED_SLABS)
  (void)inverse;
  *near_offset = origin;
  *far_offset = origin;
#else
  if (origin.x == -INFINITY) { /* bvh_slab_ray's non-finite origin (every component) */
    *near_offset = v3_splat(INFINITY);
    *far_offset = v3_splat(INFINITY);
    return;
  }
  co_vec3 oi = v3_mul(origin, inverse); /* each component at most 1e38 (bvh_slab_ray) */
  co_vec3 slack = v3_scale(v3_abs(oi), 4.76837158203125e-7f); /* 2^-21 */
  *near_offset = v3_neg(v3_add(oi, slack));
  *far_offset = v3_neg(v3_sub(oi, slack));
#endif
}

/* With COHORT_FEATURE_ALPHA a last argument is the ray's alpha seed (alpha.h). */
CO_INLINE Bvh4Ray bvh4_ray(co_vec3 org, co_vec3 dir CO_ALPHA_PARAM) {
  Bvh4Ray r;
  r.wr = watertight_ray(org, dir);
#if defined(COHORT_FEATURE_ALPHA)
  r.wr.alpha = 0; /* bvh4_continue points a copy at its tree's */
  r.wr.alpha_seed = alpha_seed;
#endif
  co_vec3 o, inv;
  bvh_slab_ray(org, dir, &o, &inv);
  co_vec3 n, f;
  bvh_slab_offsets(o, inv, &n, &f);
  r.near_ox = co_f4_splat(n.x); r.near_oy = co_f4_splat(n.y); r.near_oz = co_f4_splat(n.z);
  r.far_ox = co_f4_splat(f.x); r.far_oy = co_f4_splat(f.y); r.far_oz = co_f4_splat(f.z);
  r.ix = co_f4_splat(inv.x); r.iy = co_f4_splat(inv.y); r.iz = co_f4_splat(inv.z);
  r.near_x = dir.x < 0.0f ? 1 : 0; r.near_y = dir.y < 0.0f ? 3 : 2; r.near_z = dir.z < 0.0f ? 5 : 4;
  return r;
}

/* The four child boxes of a node (`planes`: its lo_x, hi_x, lo_y, hi_y, lo_z, hi_z, in global or
 * local memory) against ray `r`: `enter` gets each box's entry distance (at least `enter_min`, a
 * float4) and `mask` the lanes entered before `limit`. Strict: an unused lane's box at +infinity
 * gives enter = leave = +infinity. A macro so that the walk over the top levels in local memory and
 * the traversal in global memory make the same decisions from the same operations. */
#define BVH4_ENTER(planes, r, enter_min, limit, enter, mask)                                                   \
  do {                                                                                                        \
    (enter) = co_f4_max(co_f4_max(BVH_SLAB4((planes)[(r)->near_x], (r)->ix, (r)->near_ox),                    \
                                  BVH_SLAB4((planes)[(r)->near_y], (r)->iy, (r)->near_oy)),                   \
                        co_f4_max(BVH_SLAB4((planes)[(r)->near_z], (r)->iz, (r)->near_oz), (enter_min)));      \
    co_float4 leave_ = co_f4_min(co_f4_min(BVH_SLAB4((planes)[(r)->near_x ^ 1], (r)->ix, (r)->far_ox),        \
                                           BVH_SLAB4((planes)[(r)->near_y ^ 1], (r)->iy, (r)->far_oy)),       \
                                 co_f4_min(BVH_SLAB4((planes)[(r)->near_z ^ 1], (r)->iz, (r)->far_oz),        \
                                           co_f4_splat(limit)));                                               \
    (mask) = co_f4_less((enter), co_f4_scale(leave_, 1.0000004f));                                            \
  } while (0)

/* One step down from a node whose lanes `mask` (not 0) the ray enters at `enter`, by a sorting
 * network on (entry, child) over all four lanes, those not entered at +infinity so that they sort
 * last, then the entered ones but the nearest pushed by their count: the nearest goes on (*ref,
 * *ref_t), the others are pushed farthest first. No indexed private arrays (registers). */
CO_FORCE_INLINE void bvh4_descend_sorted(const Bvh4View* bvh, uint32_t mask, co_float4 enter, co_uint4 c,
                                         uint32_t* ref, float* ref_t, uint32_t* stack_ref, float* stack_t,
                                         int* sp) {
  float t0 = (mask & 1u) ? enter.x : INFINITY, t1 = (mask & 2u) ? enter.y : INFINITY;
  float t2 = (mask & 4u) ? enter.z : INFINITY, t3 = (mask & 8u) ? enter.w : INFINITY;
  uint32_t r0 = c.x, r1 = c.y, r2 = c.z, r3 = c.w;
  BVH4_ORDER(t0, r0, t1, r1);
  BVH4_ORDER(t2, r2, t3, r3);
  BVH4_ORDER(t0, r0, t2, r2);
  BVH4_ORDER(t1, r1, t3, r3);
  BVH4_ORDER(t1, r1, t2, r2);
  const uint32_t entered = co_popcount(mask);
  if (entered == 4u) { bvh4_prefetch(bvh, r3); stack_ref[*sp] = r3; stack_t[*sp] = t3; ++*sp; }
  if (entered >= 3u) { bvh4_prefetch(bvh, r2); stack_ref[*sp] = r2; stack_t[*sp] = t2; ++*sp; }
  if (entered >= 2u) { bvh4_prefetch(bvh, r1); stack_ref[*sp] = r1; stack_t[*sp] = t1; ++*sp; }
  *ref = r0; *ref_t = t0;
}

/* One step down, as bvh4_descend_sorted; where a work item runs as scalar code of its own (CPUs), a
 * step that enters one or two children (most steps) takes them without the network: one branch on
 * the count instead of five data-dependent compare-exchanges. On GPUs (COHORT_BRANCH_FREE_DESCEND:
 * the host passes it for OpenCL GPUs and Oclgrind; every CUDA device) the lanes of a warp take
 * different counts, so those branches split the warp: there every step sorts (H100, 2026-12-06:
 * naive path tracing 1.02-1.03x, sc+rg 1.01x, primary rays 0.97x; docs/design.md). Either way the
 * same children are pushed, nearest on top, so the walk finds the same hit. */
#if defined(__CUDACC__) && !defined(COHORT_BRANCH_FREE_DESCEND)
#define COHORT_BRANCH_FREE_DESCEND 1
#endif
CO_FORCE_INLINE void bvh4_descend(const Bvh4View* bvh, uint32_t mask, co_float4 enter, co_uint4 c, uint32_t* ref,
                                  float* ref_t, uint32_t* stack_ref, float* stack_t, int* sp) {
#if !defined(COHORT_BRANCH_FREE_DESCEND)
  uint32_t rest = mask & (mask - 1u);
  if (rest == 0u) {
    *ref = mask == 1u ? c.x : mask == 2u ? c.y : mask == 4u ? c.z : c.w;
    *ref_t = mask == 1u ? enter.x : mask == 2u ? enter.y : mask == 4u ? enter.z : enter.w;
    return;
  }
  if ((rest & (rest - 1u)) == 0u) {
    uint32_t a = mask & ~rest; /* the lower lane's bit */
    float ta = a == 1u ? enter.x : a == 2u ? enter.y : enter.z;
    uint32_t ra = a == 1u ? c.x : a == 2u ? c.y : c.z;
    float tb = rest == 2u ? enter.y : rest == 4u ? enter.z : enter.w;
    uint32_t rb = rest == 2u ? c.y : rest == 4u ? c.z : c.w;
    BVH4_ORDER(ta, ra, tb, rb);
    bvh4_prefetch(bvh, rb);
    stack_ref[*sp] = rb; stack_t[*sp] = tb; ++*sp;
    *ref = ra; *ref_t = ta;
    return;
  }
#endif
  bvh4_descend_sorted(bvh, mask, enter, c, ref, ref_t, stack_ref, stack_t, sp);
}

/* The order of an any-hit walk (shadow rays): farthest child first. Its answer is whether some
 * triangle blocks the segment, the same in any order, and a stacked child is never dropped (the
 * limit, tmax, only changes when the walk ends), so the descent sorts the entry distances negated
 * and the stack holds them so. Nearest first explores the clutter around the ray's origin, where a
 * shadow ray leaving a surface mostly escapes, before the far geometry that blocks it: host counts
 * on the Sponza interior's shadow rays to the sky (97 % blocked) gave 8.7 inner nodes a ray against
 * 19.3 on the 4-wide BVH and 5.3 against 12.4 on the 8-wide BVH with float planes, and exterior
 * views (7-21 % blocked) 2-12 % fewer (docs/design.md, "Any-hit order"). The image is the same. */
CO_INLINE co_float4 bvh_any_hit_order(co_float4 enter) { return co_f4_scale(enter, -1.0f); }

/* Continues a closest-hit (any_hit = 0) or any-hit (any_hit = 1) traversal at node or leaf `ref`,
 * entered at `ref_t`, with `sp` entries on the stack, into `hit` (its t the current limit).
 * `visited`, when not null, receives the number of nodes and leaves visited. */
CO_INLINE void bvh4_continue(const Bvh4View* bvh, const Bvh4Ray* r, float tmin, int any_hit, HitOut* hit, uint32_t ref,
                             float ref_t, uint32_t* stack_ref, float* stack_t, int sp, uint32_t* visited) {
  co_float4 enter_min = co_f4_splat(tmin);
  uint32_t count = 0u;
#if defined(COHORT_FEATURE_ALPHA)
  WatertightRay wr = r->wr;
  wr.alpha = &bvh->alpha;
#define BVH4_WR &wr
#else
#define BVH4_WR &r->wr
#endif
  for (;;) {
    if (!kd_beyond_hit(hit->t, ref_t)) {
      ++count;
      if (bvh4_is_leaf(ref)) {
        if (bvh4_intersect_leaf(&bvh->leaf_triangles[bvh4_leaf_first(ref)], bvh4_leaf_count(ref), BVH4_WR, tmin, hit,
                                any_hit))
          break;
      } else {
        const CO_GLOBAL Bvh4Node* n = &bvh->nodes[ref];
        co_float4 enter;
        uint32_t mask;
        BVH4_ENTER(&n->lo_x, r, enter_min, hit->t * KD_TERMINATION_SLACK, enter, mask);
        if (mask != 0u) {
          if (any_hit) enter = bvh_any_hit_order(enter);
          bvh4_descend(bvh, mask, enter, n->child, &ref, &ref_t, stack_ref, stack_t, &sp);
          continue;
        }
      }
    }
    if (sp == 0) break;
    --sp;
    ref = stack_ref[sp]; ref_t = stack_t[sp];
  }
#undef BVH4_WR
  if (visited) *visited = count;
}

/* Closest hit (any_hit = 0) or any hit (any_hit = 1) in (tmin, tmax), as kd_trace_steps (with its
 * alpha seed under COHORT_FEATURE_ALPHA): the whole traversal from the root. `steps`, when not null,
 * receives the number of nodes and leaves visited. */
CO_INLINE HitOut bvh4_trace_steps(const Bvh4View* bvh, co_vec3 org, co_vec3 dir, float tmin, float tmax,
                                  int any_hit, uint32_t* steps CO_ALPHA_PARAM) {
  HitOut hit = hit_none(tmax);
  Bvh4Ray r = bvh4_ray(org, dir CO_ALPHA_ARG(alpha_seed));
  uint32_t stack_ref[BVH4_STACK];
  float stack_t[BVH4_STACK];
  bvh4_continue(bvh, &r, tmin, any_hit, &hit, 0u /* the root */, tmin, stack_ref, stack_t, 0, steps);
  return hit;
}

#endif
