/* Closest-hit and any-hit traversal of the compressed 8-wide BVH (types.h, Bvh8Node; --tree bvh8):
 * the node-group / triangle-group traversal of Ylitie, Karras & Laine (HPG 2017). A node test
 * decodes the eight child boxes from their 8-bit planes and turns the children the ray enters into
 * one 32-bit hit mask: the inner children in bits 24-31, ordered by the ray's octant (the builder
 * put the child nearest for octant s into slot s, and bit 24 + (s ^ (7 ^ octant)) takes slot s, so
 * the highest bit is the slot that matches the ray's direction), the leaf children's triangles in
 * bits 0-23. The walk keeps two groups in registers: the node group (the children's first index,
 * the inner hits and the node's imask) and the triangle group (the first triangle and the triangle
 * hits). It takes an inner child, pushes the rest of the group (one stack entry per node, not per
 * child), tests the group's triangles and goes on into the child; an empty node group pops. Two
 * additions to the paper's walk, both from the entry distances the node test has anyway: a group
 * just made takes its nearest inner child first (the octant order, the highest bit, from then on),
 * and a pushed group carries the least entry distance of its other children, so a popped group that
 * lies wholly beyond the best hit is dropped without a node visit. On the Sponza interior (host
 * build) they cut node visits from 30.3 to 26.2 per primary-like and from 20.4 to 16.0 per diffuse
 * ray (the 4-wide BVH: 28.4 and 22.9 nodes and leaves).
 *
 * The hit is the one every other tree gives, bit for bit (docs/design.md, "The closest hit does not
 * depend on the tree"): the same watertight test (consider_triangle) on the same kept triangles,
 * the least (t, triangle index) over every triangle the ray meets, and a child box skipped only
 * when the ray enters it beyond the best t by more than KD_TERMINATION_SLACK. The boxes only have to
 * be conservative: the builder pads them as the 4-wide BVH's (bvh4_traverse.h says why), then rounds
 * lower planes down and upper planes up onto the node's grid, and a decoded plane, origin + q * 2^e,
 * is exact in float with or without fma (the builder checks it). The slab arithmetic after the
 * decode is bvh4_traverse.h's: (plane - origin) * inverse, a zero direction component taken as
 * 1e-18, the exit widened by a few ulps. A popped group is dropped only when its least entry
 * distance is beyond the best t by more than KD_TERMINATION_SLACK, as a box would be; its other
 * children are tested against the best t when entered. The order of the children changes visits,
 * never the hit. */
#ifndef COHORT_BVH8_TRAVERSE_H
#define COHORT_BVH8_TRAVERSE_H

#include "common/accel/bvh4_traverse.h"

/* Node groups on the stack (12 bytes each: first child, hits and imask, least entry distance): at
 * most one per level of the tree (a group holds one node's remaining children), and the builder
 * keeps the tree within BVH4_MAX_DEPTH levels. */
#define BVH8_STACK BVH4_MAX_DEPTH

typedef struct Bvh8View {
  const CO_GLOBAL Bvh8Node* nodes;
  const CO_GLOBAL Triangle* leaf_triangles; /* each a kept triangle's copy, its index in v0.w */
#if defined(COHORT_FEATURE_ALPHA)
  AlphaView alpha; /* set by make_scene_view */
#endif
} Bvh8View;

/* The scene's arrays as the kernels receive them: the 8-wide BVH travels in the buffers of KD
 * nodes and leaf lists, as the 4-wide one does. */
CO_INLINE Bvh8View make_bvh8_view(const CO_GLOBAL KdNode* nodes, const CO_GLOBAL uint32_t* leaf_lists) {
  Bvh8View b;
  b.nodes = (const CO_GLOBAL Bvh8Node*)nodes;
  b.leaf_triangles = (const CO_GLOBAL Triangle*)leaf_lists;
  return b;
}

/* What a walk keeps of its ray: the watertight set-up, the origin and inverse direction splatted
 * over four lanes (four slots per box test), which plane of each axis the ray enters through (the
 * upper one for a negative component) and the octant's inverse, 7 ^ octant (bit a set for a
 * negative component on axis a). */
typedef struct Bvh8Ray {
  WatertightRay wr;
  co_float4 ox, oy, oz, ix, iy, iz;
  int neg_x, neg_y, neg_z;
  uint32_t oct_inv;
} Bvh8Ray;

/* With COHORT_FEATURE_ALPHA a last argument is the ray's alpha seed (alpha.h). */
CO_INLINE Bvh8Ray bvh8_ray(co_vec3 org, co_vec3 dir CO_ALPHA_PARAM) {
  Bvh8Ray r;
  r.wr = watertight_ray(org, dir);
#if defined(COHORT_FEATURE_ALPHA)
  r.wr.alpha = 0; /* bvh8_trace_steps points a copy at its tree's */
  r.wr.alpha_seed = alpha_seed;
#endif
  co_vec3 o, inv;
  bvh_slab_ray(org, dir, &o, &inv);
  r.ox = co_f4_splat(o.x); r.oy = co_f4_splat(o.y); r.oz = co_f4_splat(o.z);
  r.ix = co_f4_splat(inv.x); r.iy = co_f4_splat(inv.y); r.iz = co_f4_splat(inv.z);
  r.neg_x = dir.x < 0.0f; r.neg_y = dir.y < 0.0f; r.neg_z = dir.z < 0.0f;
  r.oct_inv = 7u ^ ((uint32_t)r.neg_x | ((uint32_t)r.neg_y << 1) | ((uint32_t)r.neg_z << 2));
  return r;
}

/* The four bytes of a word as floats, byte 0 in x (exact: integers below 256). */
CO_INLINE co_float4 bvh8_bytes(uint32_t w) {
  return co_make_float4((float)(w & 255u), (float)((w >> 8) & 255u), (float)((w >> 16) & 255u), (float)(w >> 24));
}

/* Distances to four slots' planes on one axis: (origin + q * scale - o) * inverse. origin + q * scale
 * is the exact plane, so this rounds as bvh4's (plane - o) * inverse. */
CO_INLINE co_float4 bvh8_plane_t(uint32_t q, float origin, float scale, co_float4 o, co_float4 inverse) {
  return co_f4_mul(co_f4_sub(co_f4_add(co_f4_splat(origin), co_f4_scale(bvh8_bytes(q), scale)), o), inverse);
}

/* The hit-mask bits of four slots (`half` 0: slots 0-3, 1: slots 4-7) of node `n` (its words
 * loaded: header h, meta word `meta`, the six plane words of the half), as bvh4's BVH4_ENTER decides
 * a lane: entered at least at tmin, before `limit`, the exit widened by a few ulps. */
CO_INLINE uint32_t bvh8_half_hits(const Bvh8Ray* r, co_uint4 h, uint32_t meta, uint32_t lo_x, uint32_t lo_y,
                                  uint32_t lo_z, uint32_t hi_x, uint32_t hi_y, uint32_t hi_z, float tmin,
                                  float limit, co_float4* inner_enter) {
  float sx = co_as_float((h.w & 255u) << 23), sy = co_as_float(((h.w >> 8) & 255u) << 23);
  float sz = co_as_float(((h.w >> 16) & 255u) << 23);
  float px = co_as_float(h.x), py = co_as_float(h.y), pz = co_as_float(h.z);
  co_float4 near_x = bvh8_plane_t(r->neg_x ? hi_x : lo_x, px, sx, r->ox, r->ix);
  co_float4 far_x = bvh8_plane_t(r->neg_x ? lo_x : hi_x, px, sx, r->ox, r->ix);
  co_float4 near_y = bvh8_plane_t(r->neg_y ? hi_y : lo_y, py, sy, r->oy, r->iy);
  co_float4 far_y = bvh8_plane_t(r->neg_y ? lo_y : hi_y, py, sy, r->oy, r->iy);
  co_float4 near_z = bvh8_plane_t(r->neg_z ? hi_z : lo_z, pz, sz, r->oz, r->iz);
  co_float4 far_z = bvh8_plane_t(r->neg_z ? lo_z : hi_z, pz, sz, r->oz, r->iz);
  co_float4 enter = co_f4_max(co_f4_max(near_x, near_y), co_f4_max(near_z, co_f4_splat(tmin)));
  co_float4 leave = co_f4_min(co_f4_min(far_x, far_y), co_f4_min(far_z, co_f4_splat(limit)));
  uint32_t mask = co_f4_less(enter, co_f4_scale(leave, 1.0000004f));
  uint32_t bits = 0u, inner = 0u;
  for (uint32_t j = 0u; j < 4u; ++j) {
    uint32_t m = (meta >> (8u * j)) & 255u;
    /* an inner child's bit (24 + slot) goes to its place in the ray's octant order; an unused slot
     * (meta 0) sets nothing */
    uint32_t is_inner = (m & 0x18u) == 0x18u;
    uint32_t at = (m & 31u) ^ (is_inner ? r->oct_inv : 0u);
    bits |= ((mask >> j) & 1u) ? (m >> 5) << at : 0u;
    inner |= is_inner << j;
  }
  inner &= mask;
  *inner_enter = co_make_float4((inner & 1u) ? enter.x : INFINITY, (inner & 2u) ? enter.y : INFINITY,
                                (inner & 4u) ? enter.z : INFINITY, (inner & 8u) ? enter.w : INFINITY);
  return bits;
}

/* The hit mask of a node (its five words, loaded once): inner children in bits 24-31, leaf triangles
 * in bits 0-23. *rest_t: the least entry distance of the inner children entered, but the one the
 * walk takes first (the highest bit); +infinity without another. */
CO_INLINE uint32_t bvh8_node_hits(const Bvh8Ray* r, co_uint4 h, co_uint4 ix, co_uint4 q0, co_uint4 q1, co_uint4 q2,
                                  float tmin, float limit, float* rest_t, uint32_t* first_bit) {
  co_float4 e0, e1;
  uint32_t hits = bvh8_half_hits(r, h, ix.z, q0.x, q0.z, q1.x, q1.z, q2.x, q2.z, tmin, limit, &e0) |
                  bvh8_half_hits(r, h, ix.w, q0.y, q0.w, q1.y, q1.w, q2.y, q2.w, tmin, limit, &e1);
  /* the nearest inner child entered */
  float best = e0.x;
  uint32_t first = 0u;
  if (e0.y < best) { best = e0.y; first = 1u; }
  if (e0.z < best) { best = e0.z; first = 2u; }
  if (e0.w < best) { best = e0.w; first = 3u; }
  if (e1.x < best) { best = e1.x; first = 4u; }
  if (e1.y < best) { best = e1.y; first = 5u; }
  if (e1.z < best) { best = e1.z; first = 6u; }
  if (e1.w < best) { best = e1.w; first = 7u; }
  *first_bit = 24u + (first ^ r->oct_inv);
  e0 = co_make_float4(first == 0u ? INFINITY : e0.x, first == 1u ? INFINITY : e0.y, first == 2u ? INFINITY : e0.z,
                      first == 3u ? INFINITY : e0.w);
  e1 = co_make_float4(first == 4u ? INFINITY : e1.x, first == 5u ? INFINITY : e1.y, first == 6u ? INFINITY : e1.z,
                      first == 7u ? INFINITY : e1.w);
  co_float4 e = co_f4_min(e0, e1);
  float a = e.x < e.y ? e.x : e.y, b = e.z < e.w ? e.z : e.w;
  *rest_t = a < b ? a : b;
  return hits;
}

/* Closest hit (any_hit = 0) or any hit (any_hit = 1) in (tmin, tmax), as kd_trace_steps (with its
 * alpha seed under COHORT_FEATURE_ALPHA). `steps`, when not null, receives the nodes visited plus
 * the triangles tested. */
CO_INLINE HitOut bvh8_trace_steps(const Bvh8View* bvh, co_vec3 org, co_vec3 dir, float tmin, float tmax,
                                  int any_hit, uint32_t* steps CO_ALPHA_PARAM) {
  HitOut hit = hit_none(tmax);
  Bvh8Ray r = bvh8_ray(org, dir CO_ALPHA_ARG(alpha_seed));
#if defined(COHORT_FEATURE_ALPHA)
  r.wr.alpha = &bvh->alpha;
#endif
  uint32_t stack_base[BVH8_STACK], stack_hits[BVH8_STACK];
  float stack_t[BVH8_STACK];
  int sp = 0;
  /* the root: the one inner child of a parent with no inner slots before it */
  uint32_t node_base = 0u, node_hits = 0x80000000u;
  float node_t = tmin; /* no child of the group but the one taken first is entered before it */
  uint32_t first_bit = 31u; /* the child to take first from a group just made */
  int fresh = 1;
  uint32_t tri_base = 0u, tri_hits = 0u;
  uint32_t count = 0u;
  for (;;) {
    if (node_hits > 0x00ffffffu) {
      uint32_t bit = fresh ? first_bit : 31u - co_clz(node_hits);
      node_hits &= ~(1u << bit);
      uint32_t slot = (bit - 24u) ^ r.oct_inv;
      /* inner children are stored in slot order: this one follows those of the slots before it */
      uint32_t index = node_base + co_popcount(node_hits & ((1u << slot) - 1u));
      if (node_hits > 0x00ffffffu) {
        stack_base[sp] = node_base; stack_hits[sp] = node_hits; stack_t[sp] = node_t; ++sp;
      }
      const CO_GLOBAL Bvh8Node* n = &bvh->nodes[index];
      co_uint4 h = n->header, ix = n->index;
      uint32_t hits =
          bvh8_node_hits(&r, h, ix, n->q[0], n->q[1], n->q[2], tmin, hit.t * KD_TERMINATION_SLACK, &node_t, &first_bit);
      fresh = 1;
      ++count;
      node_base = ix.x;
      node_hits = (hits & 0xff000000u) | (h.w >> 24);
      tri_base = ix.y;
      tri_hits = hits & 0x00ffffffu;
    }
    int answered = 0;
    while (tri_hits != 0u) {
      uint32_t bit = 31u - co_clz(tri_hits);
      tri_hits &= ~(1u << bit);
      ++count;
      const CO_GLOBAL Triangle* t = &bvh->leaf_triangles[tri_base + bit];
      if (consider_triangle(&r.wr, t, co_as_uint(t->v0.w), tmin, &hit, any_hit)) {
        answered = 1;
        break;
      }
    }
    if (answered) break;
    /* a group whose children are all entered beyond the best hit is dropped */
    while (node_hits <= 0x00ffffffu && sp > 0) {
      --sp;
      node_base = stack_base[sp]; node_hits = stack_hits[sp]; node_t = stack_t[sp];
      fresh = 0;
      if (kd_beyond_hit(hit.t, node_t)) node_hits = 0u;
    }
    if (node_hits <= 0x00ffffffu) break;
  }
  if (steps) *steps = count;
  return hit;
}

#endif
