/* Closest-hit and any-hit traversal of the 8-wide BVH with float planes (types.h, Bvh8fNode; --tree
 * bvh8f): the 4-wide walk (bvh4_traverse.h) at twice the width, for CPUs. PoCL runs a work item's
 * walk as scalar code, so the only SIMD a walk gets is from explicit vector types: the 4-wide node
 * test is SSE-wide, and an AVX CPU tests eight boxes in the same instructions with float8 (one
 * vsubps, vmulps, vmaxps or vminps per plane row). The nodes are the 4-wide ones' with eight lanes
 * (six rows of eight floats, then the eight references), built by the same collapse of a binary SAH
 * tree (runtime/accel/wide_collapse.h) whose leaves are blocks of four triangles (Triangle4), tested
 * four to a float4 step (intersect_triangle4).
 *
 * The hit is the one every other tree gives, bit for bit (docs/design.md, "The closest hit does not
 * depend on the tree"): the same watertight test lane for lane, taken as consider_triangle takes it
 * (record_hit), on the same kept triangles, the least (t, triangle index) over every triangle the ray
 * meets, and each box tested lane for lane with BVH4_ENTER's operations: the boxes padded as the
 * 4-wide BVH's, a zero direction component taken as 1e-18 (bvh4_inverse), the exit widened by a few
 * ulps, a box skipped only when it starts beyond the best t by more than KD_TERMINATION_SLACK. The
 * order of the children changes visits, never the hit. */
#ifndef COHORT_BVH8F_TRAVERSE_H
#define COHORT_BVH8F_TRAVERSE_H

#include "common/accel/bvh4_traverse.h"

/* Entries of the traversal stack: a step leaves at most seven children on it, and the tree is at
 * most BVH4_MAX_DEPTH levels deep (a step writes all it enters, then takes the nearest back). */
#define BVH8F_STACK (7 * BVH4_MAX_DEPTH + 1)

typedef struct Bvh8fView {
  const CO_GLOBAL Bvh8fNode* nodes;
  const CO_GLOBAL Triangle4* leaf_blocks; /* the leaves' kept triangles, four to a block */
#if defined(COHORT_FEATURE_ALPHA)
  AlphaView alpha; /* set by make_scene_view */
#endif
} Bvh8fView;

/* The scene's arrays as the kernels receive them: the tree travels in the buffers of KD nodes and
 * leaf lists, as the 4-wide one does. */
CO_INLINE Bvh8fView make_bvh8f_view(const CO_GLOBAL KdNode* nodes, const CO_GLOBAL uint32_t* leaf_lists) {
  Bvh8fView b;
  b.nodes = (const CO_GLOBAL Bvh8fNode*)nodes;
  b.leaf_blocks = (const CO_GLOBAL Triangle4*)leaf_lists;
  return b;
}

/* Starts loading a pushed child's cache lines for when it is popped (bvh4_prefetch says why): a
 * leaf's blocks (the lines of the first and last byte and the one between), an inner node's four. */
CO_INLINE void bvh8f_prefetch(const Bvh8fView* bvh, uint32_t ref) {
  if (bvh4_is_leaf(ref)) {
    const CO_GLOBAL char* first = (const CO_GLOBAL char*)&bvh->leaf_blocks[bvh4_leaf_first(ref)];
    co_prefetch(first);
    co_prefetch(first + 64);
    co_prefetch(first + bvh8f_leaf_blocks(bvh4_leaf_count(ref)) * sizeof(Triangle4) - 1u);
  } else {
    const CO_GLOBAL char* node = (const CO_GLOBAL char*)&bvh->nodes[ref];
    co_prefetch(node);
    co_prefetch(node + 64);
    co_prefetch(node + 128);
    co_prefetch(node + 192);
  }
}

/* A walk's ray: the watertight set-up, the origin and inverse direction over eight lanes, and the
 * plane row each slab is entered through (Bvh4Ray says why that picks what a min and a max would). */
typedef struct Bvh8fRay {
  WatertightRay wr;
  co_float8 near_ox, near_oy, near_oz, far_ox, far_oy, far_oz; /* bvh_slab_offsets */
  co_float8 ix, iy, iz;
  int near_x, near_y, near_z;
} Bvh8fRay;

/* With COHORT_FEATURE_ALPHA a last argument is the ray's alpha seed (alpha.h). */
CO_INLINE Bvh8fRay bvh8f_ray(co_vec3 org, co_vec3 dir CO_ALPHA_PARAM) {
  Bvh8fRay r;
  r.wr = watertight_ray(org, dir);
#if defined(COHORT_FEATURE_ALPHA)
  r.wr.alpha = 0; /* bvh8f_trace_steps points a copy at its tree's */
  r.wr.alpha_seed = alpha_seed;
#endif
  co_vec3 o, inv;
  bvh_slab_ray(org, dir, &o, &inv);
  co_vec3 n, f;
  bvh_slab_offsets(o, inv, &n, &f);
  r.near_ox = co_f8_splat(n.x); r.near_oy = co_f8_splat(n.y); r.near_oz = co_f8_splat(n.z);
  r.far_ox = co_f8_splat(f.x); r.far_oy = co_f8_splat(f.y); r.far_oz = co_f8_splat(f.z);
  r.ix = co_f8_splat(inv.x); r.iy = co_f8_splat(inv.y); r.iz = co_f8_splat(inv.z);
  r.near_x = dir.x < 0.0f ? 1 : 0; r.near_y = dir.y < 0.0f ? 3 : 2; r.near_z = dir.z < 0.0f ? 5 : 4;
  return r;
}

/* The eight child boxes of node `n` against ray `r`: BVH4_ENTER's operations lane for lane. Writes
 * each box's entry distance (at least tmin) to enter[0-7] and returns the mask of the boxes entered
 * before `limit`, lane i in bit i. */
CO_FORCE_INLINE uint32_t bvh8f_enter(const CO_GLOBAL Bvh8fNode* n, const Bvh8fRay* r, float tmin, float limit,
                                     float* enter) {
  co_float8 e = co_f8_max(co_f8_max(BVH_SLAB8(co_f8_load(n->planes[r->near_x]), r->ix, r->near_ox),
                                    BVH_SLAB8(co_f8_load(n->planes[r->near_y]), r->iy, r->near_oy)),
                          co_f8_max(BVH_SLAB8(co_f8_load(n->planes[r->near_z]), r->iz, r->near_oz),
                                    co_f8_splat(tmin)));
  co_float8 l = co_f8_min(co_f8_min(BVH_SLAB8(co_f8_load(n->planes[r->near_x ^ 1]), r->ix, r->far_ox),
                                    BVH_SLAB8(co_f8_load(n->planes[r->near_y ^ 1]), r->iy, r->far_oy)),
                          co_f8_min(BVH_SLAB8(co_f8_load(n->planes[r->near_z ^ 1]), r->iz, r->far_oz),
                                    co_f8_splat(limit)));
  co_f8_store(e, enter);
  return co_f8_less(e, co_f8_scale(l, 1.0000004f));
}

/* The lowest set bit's index of a mask that is not 0. */
CO_INLINE uint32_t bvh8f_lowest(uint32_t mask) { return 31u - co_clz(mask & (0u - mask)); }

/* One step down from node `n`, whose lanes `mask` (not 0) the ray enters at enter[lane]: goes on
 * with the nearest child (*ref, *ref_t) and pushes the others, farthest deepest, as bvh4_descend. */
CO_FORCE_INLINE void bvh8f_descend(const Bvh8fView* bvh, const CO_GLOBAL Bvh8fNode* n, uint32_t mask,
                                   const float* enter, uint32_t* ref, float* ref_t, uint32_t* stack_ref,
                                   float* stack_t, int* sp) {
  uint32_t lane = bvh8f_lowest(mask);
  mask &= mask - 1u;
  if (mask == 0u) { /* one lane entered (most steps): no stack */
    *ref = n->child[lane];
    *ref_t = enter[lane];
    return;
  }
  /* two or more: an insertion sort onto the stack, nearest on top, then the top taken back */
  int base = *sp, top = *sp;
  for (;;) {
    float t = enter[lane];
    uint32_t c = n->child[lane];
    int k = top;
    while (k > base && stack_t[k - 1] < t) {
      stack_t[k] = stack_t[k - 1];
      stack_ref[k] = stack_ref[k - 1];
      --k;
    }
    stack_t[k] = t;
    stack_ref[k] = c;
    ++top;
    if (mask == 0u) break;
    lane = bvh8f_lowest(mask);
    mask &= mask - 1u;
  }
  --top;
  *ref = stack_ref[top];
  *ref_t = stack_t[top];
  for (int k = base; k < top; ++k) bvh8f_prefetch(bvh, stack_ref[k]);
  *sp = top;
}

/* The `count` triangles of the leaf whose blocks start at `block`, four at a time
 * (intersect_triangle4), each lane hit taken in lane order as the triangle after triangle of
 * consider_triangle would take it (record_hit); the unused lanes of the last block are masked off. */
CO_INLINE int bvh8f_intersect_leaf(const CO_GLOBAL Triangle4* block, uint32_t count, const WatertightRay* wr,
                                   float ray_tmin, HitOut* hit, int any_hit) {
  for (uint32_t first = 0; first < count; first += 4u, ++block) {
    float t[4], u[4], v[4];
    uint32_t lanes = intersect_triangle4(wr, block, ray_tmin, any_hit ? hit->t : INFINITY, t, u, v);
    if (count - first < 4u) lanes &= (1u << (count - first)) - 1u;
    while (lanes != 0u) {
      const uint32_t lane = bvh8f_lowest(lanes);
      lanes &= lanes - 1u;
      if (record_hit(wr, block->index[lane], t[lane], u[lane], v[lane], hit, any_hit)) return 1;
    }
  }
  return 0;
}

/* A walk's ray and its answer: the ray, its best hit so far and the nodes and leaves it visited. The
 * walk itself runs inside one function (bvh8f_walk_run, bvh8f_trace_pair) from a Bvh8fAt and a
 * Bvh8fStack of that function's own, so that a work item can step two walks in turn. */
typedef struct Bvh8fWalk {
  Bvh8fRay r;
  HitOut hit;
  float tmin;
  int any_hit;
  uint32_t count; /* nodes and leaves visited */
} Bvh8fWalk;

/* Where a walk stands: the node or leaf to visit next, where the ray enters it, the stack's depth
 * and the visits so far. Kept apart from the stack's arrays and from the Bvh8fWalk that the caller
 * holds, in a local whose address only the forced-inline step sees, so that the compiler holds it in
 * registers: reached through a pointer, or beside an array indexed at run time, it stayed in memory,
 * a store and a reload on every link of the walk's chain of dependent loads. */
typedef struct Bvh8fAt {
  uint32_t ref;
  float ref_t;
  int sp;
  uint32_t count;
} Bvh8fAt;

typedef struct Bvh8fStack {
  uint32_t ref[BVH8F_STACK];
  float t[BVH8F_STACK];
} Bvh8fStack;

CO_FORCE_INLINE void bvh8f_walk_start(const Bvh8fView* bvh, Bvh8fWalk* w, co_vec3 org, co_vec3 dir, float tmin,
                                      float tmax, int any_hit CO_ALPHA_PARAM) {
  w->hit = hit_none(tmax);
  w->r = bvh8f_ray(org, dir CO_ALPHA_ARG(alpha_seed));
#if defined(COHORT_FEATURE_ALPHA)
  w->r.wr.alpha = &bvh->alpha;
#else
  (void)bvh;
#endif
  w->tmin = tmin;
  w->any_hit = any_hit;
  w->count = 0u;
}

/* A started walk at the root. (An out parameter, not a returned struct: a forced-inline function
 * returning one leaves a noalias scope declaration behind, which Oclgrind cannot run.) */
CO_FORCE_INLINE void bvh8f_walk_root(const Bvh8fWalk* w, Bvh8fAt* at) {
  at->ref = 0u;
  at->ref_t = w->tmin;
  at->sp = 0;
  at->count = 0u;
}

/* Visits the walk's next node or leaf (or pops one it need not visit); 0 when the walk is over. */
CO_FORCE_INLINE int bvh8f_walk_step(const Bvh8fView* bvh, Bvh8fWalk* w, Bvh8fAt* at, Bvh8fStack* stack) {
  if (!kd_beyond_hit(w->hit.t, at->ref_t)) {
    ++at->count;
    if (bvh4_is_leaf(at->ref)) {
      if (bvh8f_intersect_leaf(&bvh->leaf_blocks[bvh4_leaf_first(at->ref)], bvh4_leaf_count(at->ref), &w->r.wr,
                               w->tmin, &w->hit, w->any_hit))
        return 0;
    } else {
      const CO_GLOBAL Bvh8fNode* n = &bvh->nodes[at->ref];
      float enter[8];
      uint32_t mask = bvh8f_enter(n, &w->r, w->tmin, w->hit.t * KD_TERMINATION_SLACK, enter);
      if (mask != 0u) {
        /* an any-hit walk takes the farthest child first (bvh4_traverse.h, bvh_any_hit_order) */
        if (w->any_hit)
          for (int k = 0; k < 8; ++k) enter[k] = -enter[k];
        bvh8f_descend(bvh, n, mask, enter, &at->ref, &at->ref_t, stack->ref, stack->t, &at->sp);
        return 1;
      }
    }
  }
  if (at->sp == 0) return 0;
  --at->sp;
  at->ref = stack->ref[at->sp];
  at->ref_t = stack->t[at->sp];
  return 1;
}

/* A started walk to its end: w->hit is then its hit and w->count its visits. */
CO_INLINE void bvh8f_walk_run(const Bvh8fView* bvh, Bvh8fWalk* w) {
  Bvh8fAt at;
  Bvh8fStack stack;
  bvh8f_walk_root(w, &at);
  while (bvh8f_walk_step(bvh, w, &at, &stack)) {
  }
  w->count = at.count;
}

/* Closest hit (any_hit = 0) or any hit (any_hit = 1) in (tmin, tmax), as kd_trace_steps (with its
 * alpha seed under COHORT_FEATURE_ALPHA). `steps`, when not null, receives the number of nodes and
 * leaves visited. */
CO_INLINE HitOut bvh8f_trace_steps(const Bvh8fView* bvh, co_vec3 org, co_vec3 dir, float tmin, float tmax,
                                   int any_hit, uint32_t* steps CO_ALPHA_PARAM) {
  Bvh8fWalk w;
  bvh8f_walk_start(bvh, &w, org, dir, tmin, tmax, any_hit CO_ALPHA_ARG(alpha_seed));
  bvh8f_walk_run(bvh, &w);
  if (steps) *steps = w.count;
  return w.hit;
}

/* Two started walks to their ends, a step of each in turn: each walk is one chain of dependent
 * loads, and two chains in one instruction stream let the core wait on both nodes' loads at once.
 * Each walk visits what it visits alone, so each gets bvh8f_trace_steps' hit. */
CO_INLINE void bvh8f_trace_pair(const Bvh8fView* bvh, Bvh8fWalk* a, Bvh8fWalk* b) {
  Bvh8fAt at_a, at_b;
  Bvh8fStack stack_a, stack_b;
  bvh8f_walk_root(a, &at_a);
  bvh8f_walk_root(b, &at_b);
  int more_a = 1, more_b = 1;
  while (more_a && more_b) {
    more_a = bvh8f_walk_step(bvh, a, &at_a, &stack_a);
    more_b = bvh8f_walk_step(bvh, b, &at_b, &stack_b);
  }
  while (more_a) more_a = bvh8f_walk_step(bvh, a, &at_a, &stack_a);
  while (more_b) more_b = bvh8f_walk_step(bvh, b, &at_b, &stack_b);
  a->count = at_a.count;
  b->count = at_b.count;
}

/* ---- Packets: eight rays of one octant walked together ---------------------------------------
 * Rays that start together (a pixel's camera rays: one eye, directions within the pixel) meet the
 * same nodes. A packet walks the tree once for all of them: one stack, one order of the children and
 * one load of a node, each box tested against the eight rays at once (a float8 across the rays, where
 * a ray's own walk has the eight boxes across the lanes). Each lane computes its ray's own
 * bvh8f_enter operations (the same entry plane rows, as the packet's rays share their direction
 * signs), and each ray tests the leaves' triangles with its own watertight ray, so it keeps its own
 * hit: the order of the visits changes nodes visited, never the hit. A child goes on the stack with
 * the rays that enter it and where each enters, so a ray leaves a popped node that its best hit so
 * far lies before (kd_beyond_hit), as its own walk would skip it. */
#define BVH8F_PACKET 8

typedef struct Bvh8fPacket {
  WatertightRay wr[BVH8F_PACKET];
  float near_o[3][BVH8F_PACKET], far_o[3][BVH8F_PACKET], inv[3][BVH8F_PACKET]; /* axis by axis, lane l = ray l */
  HitOut hit[BVH8F_PACKET];
  uint32_t count[BVH8F_PACKET]; /* nodes and leaves each ray visited */
  uint32_t lanes;               /* the rays in the packet, lane i in bit i */
  int near_x, near_y, near_z;   /* the plane rows its rays enter a box through (Bvh8fRay) */
} Bvh8fPacket;

/* An empty packet whose rays will enter boxes through the rows of direction `dir`'s signs. */
CO_INLINE void bvh8f_packet_begin(Bvh8fPacket* k, co_vec3 dir) {
  for (int a = 0; a < 3; ++a) { /* lanes without a ray compute on finite values, then are masked off */
    co_f8_store(co_f8_splat(0.0f), k->near_o[a]);
    co_f8_store(co_f8_splat(0.0f), k->far_o[a]);
    co_f8_store(co_f8_splat(1.0f), k->inv[a]);
  }
  for (int l = 0; l < BVH8F_PACKET; ++l) {
    k->hit[l] = hit_none(INFINITY);
    k->count[l] = 0u;
  }
  k->lanes = 0u;
  k->near_x = dir.x < 0.0f ? 1 : 0; k->near_y = dir.y < 0.0f ? 3 : 2; k->near_z = dir.z < 0.0f ? 5 : 4;
}

/* Whether a ray of direction `dir` enters boxes through the packet's rows. */
CO_INLINE int bvh8f_packet_fits(const Bvh8fPacket* k, co_vec3 dir) {
  return (dir.x < 0.0f ? 1 : 0) == k->near_x && (dir.y < 0.0f ? 3 : 2) == k->near_y &&
         (dir.z < 0.0f ? 5 : 4) == k->near_z;
}

#if defined(COHORT_FEATURE_ALPHA)
#define BVH8F_ALPHA_SEEDS_PARAM , const uint32_t* alpha_seeds
#else
#define BVH8F_ALPHA_SEEDS_PARAM
#endif

/* Lanes 0 to n-1 (n from 1 to BVH8F_PACKET) of an empty packet `k` take the closest-hit rays from
 * (ox, oy, oz)[l] along (dx, dy, dz)[l] in (0, infinity); every ray must fit. Lane l holds what its
 * ray alone gives: watertight_ray's shear, and bvh_slab_ray's origin and inverse direction with
 * bvh_slab_offsets' offsets, axis by axis. The arrays hold BVH8F_PACKET entries: those from n on are
 * any finite ray (the caller repeats lane 0's), computed and dropped. Why eight at once: on a CPU
 * each work item is scalar code, and a ray's set-up is a chain of six divisions, selects and
 * products that one ray at a time leaves the core waiting on (perf: 8.6 % of the DamagedHelmet's
 * render samples in the one-ray set-up this replaced, a fifth of them on its first division). Here
 * the lanes' set-ups run in loops of a fixed count over plain arrays, which a CPU compiler makes
 * one vector operation per step; each lane runs those functions' operations (bvh_slab_ray's
 * divisions in a loop of their own), so the packet holds the same bits. */
CO_INLINE void bvh8f_packet_add_all(const Bvh8fView* bvh, Bvh8fPacket* k, uint32_t n, const float* ox, const float* oy,
                                    const float* oz, const float* dx, const float* dy,
                                    const float* dz BVH8F_ALPHA_SEEDS_PARAM) {
  float row[10][BVH8F_PACKET]; /* row_x, row_y, row_z and sz of each lane's watertight ray */
  float near_o[3][BVH8F_PACKET], far_o[3][BVH8F_PACKET], inv[3][BVH8F_PACKET];
  for (uint32_t l = 0u; l < BVH8F_PACKET; ++l) {
    const WatertightRay w = watertight_ray(v3(ox[l], oy[l], oz[l]), v3(dx[l], dy[l], dz[l]));
    row[0][l] = w.row_x.x; row[1][l] = w.row_x.y; row[2][l] = w.row_x.z;
    row[3][l] = w.row_y.x; row[4][l] = w.row_y.y; row[5][l] = w.row_y.z;
    row[6][l] = w.row_z.x; row[7][l] = w.row_z.y; row[8][l] = w.row_z.z;
    row[9][l] = w.sz;
  }
  float div[3][BVH8F_PACKET]; /* bvh_slab_ray's divisions, then the rest of it */
  for (uint32_t l = 0u; l < BVH8F_PACKET; ++l) {
    div[0][l] = bvh4_inverse(dx[l]);
    div[1][l] = bvh4_inverse(dy[l]);
    div[2][l] = bvh4_inverse(dz[l]);
  }
  for (uint32_t l = 0u; l < BVH8F_PACKET; ++l) {
    co_vec3 o, iv, nn, f;
    bvh_slab_ray_inverted(v3(ox[l], oy[l], oz[l]), v3(div[0][l], div[1][l], div[2][l]), &o, &iv);
    bvh_slab_offsets(o, iv, &nn, &f);
    near_o[0][l] = nn.x; near_o[1][l] = nn.y; near_o[2][l] = nn.z;
    far_o[0][l] = f.x; far_o[1][l] = f.y; far_o[2][l] = f.z;
    inv[0][l] = iv.x; inv[1][l] = iv.y; inv[2][l] = iv.z;
  }
  for (uint32_t l = 0u; l < n; ++l) {
    WatertightRay* w = &k->wr[l];
    w->org = v3(ox[l], oy[l], oz[l]);
    w->row_x = v3(row[0][l], row[1][l], row[2][l]);
    w->row_y = v3(row[3][l], row[4][l], row[5][l]);
    w->row_z = v3(row[6][l], row[7][l], row[8][l]);
    w->sz = row[9][l];
#if defined(COHORT_FEATURE_ALPHA)
    w->alpha = &bvh->alpha;
    w->alpha_seed = alpha_seeds[l];
#endif
    for (int a = 0; a < 3; ++a) {
      k->near_o[a][l] = near_o[a][l];
      k->far_o[a][l] = far_o[a][l];
      k->inv[a][l] = inv[a][l];
    }
  }
#if !defined(COHORT_FEATURE_ALPHA)
  (void)bvh;
#endif
  k->lanes = (1u << n) - 1u;
}

/* The closest hits of the packet's rays, each the one bvh8f_trace_steps gives it. */
CO_INLINE void bvh8f_trace_packet(const Bvh8fView* bvh, Bvh8fPacket* k) {
  uint32_t stack_ref[BVH8F_STACK], stack_lanes[BVH8F_STACK];
  float stack_t[BVH8F_STACK][BVH8F_PACKET];
  float best[BVH8F_PACKET], ref_t[BVH8F_PACKET];
  for (int l = 0; l < BVH8F_PACKET; ++l) best[l] = k->hit[l].t;
  co_f8_store(co_f8_splat(0.0f), ref_t);
  const co_float8 nox = co_f8_load(k->near_o[0]), noy = co_f8_load(k->near_o[1]), noz = co_f8_load(k->near_o[2]);
  const co_float8 fox = co_f8_load(k->far_o[0]), foy = co_f8_load(k->far_o[1]), foz = co_f8_load(k->far_o[2]);
  const co_float8 ix = co_f8_load(k->inv[0]), iy = co_f8_load(k->inv[1]), iz = co_f8_load(k->inv[2]);
  const int rx = k->near_x, ry = k->near_y, rz = k->near_z;
  int sp = 0;
  uint32_t ref = 0u, lanes = k->lanes;
  co_count8 visits = co_c8_zero(); /* each ray's, lane by lane */
  for (;;) {
    /* the rays whose own walk would visit this node */
    const co_float8 limit = co_f8_scale(co_f8_load(best), KD_TERMINATION_SLACK);
    const uint32_t live = lanes & ~co_f8_less(limit, co_f8_load(ref_t));
    visits = co_c8_count(visits, live);
    if (live != 0u) {
      if (bvh4_is_leaf(ref)) {
        const CO_GLOBAL Triangle4* block = &bvh->leaf_blocks[bvh4_leaf_first(ref)];
        for (uint32_t rest = live; rest != 0u; rest &= rest - 1u) {
          const uint32_t l = bvh8f_lowest(rest);
          bvh8f_intersect_leaf(block, bvh4_leaf_count(ref), &k->wr[l], 0.0f, &k->hit[l], 0);
          best[l] = k->hit[l].t;
        }
      } else {
        const CO_GLOBAL Bvh8fNode* n = &bvh->nodes[ref];
        uint32_t child_ref[8], child_lanes[8], order[8], entered = 0u;
        float child_t[8][BVH8F_PACKET], key[8];
        for (uint32_t c = 0u; c < 8u; ++c) {
          if (n->child[c] == BVH4_EMPTY) break; /* the collapse fills lanes from 0 (wide_collapse.h) */
          /* bvh8f_enter's operations, lane l for ray l */
          const co_float8 e =
              co_f8_max(co_f8_max(BVH_SLAB8(co_f8_splat(n->planes[rx][c]), ix, nox),
                                  BVH_SLAB8(co_f8_splat(n->planes[ry][c]), iy, noy)),
                        co_f8_max(BVH_SLAB8(co_f8_splat(n->planes[rz][c]), iz, noz), co_f8_splat(0.0f)));
          const co_float8 x =
              co_f8_min(co_f8_min(BVH_SLAB8(co_f8_splat(n->planes[rx ^ 1][c]), ix, fox),
                                  BVH_SLAB8(co_f8_splat(n->planes[ry ^ 1][c]), iy, foy)),
                        co_f8_min(BVH_SLAB8(co_f8_splat(n->planes[rz ^ 1][c]), iz, foz), limit));
          const uint32_t m = co_f8_less(e, co_f8_scale(x, 1.0000004f)) & live;
          if (m == 0u) continue;
          /* an insertion sort by the entry of the child's first ray, nearest last */
          const uint32_t slot = entered++;
          co_f8_store(e, child_t[slot]);
          child_ref[slot] = n->child[c];
          child_lanes[slot] = m;
          key[slot] = child_t[slot][bvh8f_lowest(m)];
          uint32_t j = slot;
          while (j > 0u && key[order[j - 1u]] < key[slot]) {
            order[j] = order[j - 1u];
            --j;
          }
          order[j] = slot;
        }
        if (entered != 0u) {
          for (uint32_t j = 0u; j + 1u < entered; ++j) {
            const uint32_t slot = order[j];
            stack_ref[sp] = child_ref[slot];
            stack_lanes[sp] = child_lanes[slot];
            co_f8_store(co_f8_load(child_t[slot]), stack_t[sp]);
            bvh8f_prefetch(bvh, stack_ref[sp]);
            ++sp;
          }
          const uint32_t slot = order[entered - 1u];
          ref = child_ref[slot];
          lanes = child_lanes[slot];
          co_f8_store(co_f8_load(child_t[slot]), ref_t);
          continue;
        }
      }
    }
    if (sp == 0) break;
    --sp;
    ref = stack_ref[sp];
    lanes = stack_lanes[sp];
    co_f8_store(co_f8_load(stack_t[sp]), ref_t);
  }
  int32_t counted[BVH8F_PACKET];
  co_c8_store(visits, counted);
  for (int l = 0; l < BVH8F_PACKET; ++l) k->count[l] += (uint32_t)counted[l];
}

#endif
