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
 * lower planes down and upper planes up onto the node's grid, and the node test (bvh8_grid) moves
 * each slab's distance outwards by more than its roundings, so a box is entered more often than
 * exactly, never less. A zero direction component is taken as 1e-18 and the exit is widened by a few
 * ulps, as the 4-wide BVH's. A popped group is dropped only when its least entry
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

/* What a walk keeps of its ray: the watertight set-up, the origin and inverse direction
 * (bvh_slab_ray), which plane of each axis the ray enters through (the upper one for a negative
 * component) and the octant's inverse, 7 ^ octant (bit a set for a negative component on axis a). */
typedef struct Bvh8Ray {
  WatertightRay wr;
  co_vec3 o, inv;
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
  bvh_slab_ray(org, dir, &r.o, &r.inv);
  r.neg_x = dir.x < 0.0f; r.neg_y = dir.y < 0.0f; r.neg_z = dir.z < 0.0f;
  r.oct_inv = 7u ^ ((uint32_t)r.neg_x | ((uint32_t)r.neg_y << 1) | ((uint32_t)r.neg_z << 2));
  return r;
}

/* The four bytes of a word as floats, byte 0 in x (exact: integers below 256). */
CO_INLINE co_float4 bvh8_bytes(uint32_t w) {
  return co_make_float4((float)(w & 255u), (float)((w >> 8) & 255u), (float)((w >> 16) & 255u), (float)(w >> 24));
}

/* A node's grid as the ray sees it, one axis a component: the distance to plane q of an axis is
 * q * step + near for the planes the ray enters through and q * step + far for those it leaves
 * through. The exact distance is (origin + q 2^e - o) * inverse = q * (2^e inverse) + (origin - o) *
 * inverse: step is exact (a power of two times the inverse; the builder keeps 2^e at least 2^-100,
 * so no product is subnormal for a direction component up to 2^26), and the offset b = (origin - o) *
 * inverse is rounded twice, within 2^-23 |b|. near and far move b by s = 2^-21 (|b| + 256 |step|):
 * enough for b's roundings, their own and, unfused, the rounding of q * step (at most 2^-24 255
 * |step|), so before the last rounding (the fma's, or the add's) the entry distance is never above
 * and the exit never below the exact one, and the exit's widening by a few ulps covers that last
 * rounding as it does the 4-wide BVH's (bvh4_traverse.h, bvh_slab_offsets). The boxes grow by about
 * 2^-21 of the distance from the node's origin to the ray's in space, far below their padding: more
 * visits now and then, never a box missed, so the hit does not change. One fma a plane (Ylitie et
 * al.'s decode) where it was a conversion and four float operations. s is held below FLT_MAX so that
 * bvh_slab_ray's -infinity origin (b = +infinity) puts every plane at +infinity, not NaN. The builder
 * takes vertices within 1e19 of the origin, so q * step (at most twice a node's extent times
 * |inverse| <= 1e18) and b (|o inverse| <= 1e38 by bvh_slab_ray) stay finite, and so does their sum
 * for any node a finite hit can lie in. */
typedef struct Bvh8Grid {
  co_vec3 step, near, far;
} Bvh8Grid;

CO_INLINE float bvh8_slack(float b, float step) {
  float s = (fabs(b) + fabs(step) * 256.0f) * 4.76837158203125e-7f; /* 2^-21 */
  return s < 3.40282347e38f ? s : 3.40282347e38f; /* FLT_MAX */
}

CO_INLINE Bvh8Grid bvh8_grid(const Bvh8Ray* r, co_uint4 h) {
  Bvh8Grid g;
  co_vec3 scale = v3(co_as_float((h.w & 255u) << 23), co_as_float(((h.w >> 8) & 255u) << 23),
                     co_as_float(((h.w >> 16) & 255u) << 23));
  co_vec3 origin = v3(co_as_float(h.x), co_as_float(h.y), co_as_float(h.z));
  g.step = v3_mul(scale, r->inv);
  co_vec3 b = v3_mul(v3_sub(origin, r->o), r->inv);
  co_vec3 s = v3(bvh8_slack(b.x, g.step.x), bvh8_slack(b.y, g.step.y), bvh8_slack(b.z, g.step.z));
  g.near = v3_sub(b, s);
  g.far = v3_add(b, s);
  return g;
}

/* Distances to four slots' planes on one axis (their bytes in q): q * step + offset, in one rounding
 * where the device fuses the slabs, in two where it does not (bvh4_traverse.h, BVH_SLAB4). */
#if defined(COHORT_UNFUSED_SLABS)
#define BVH8_PLANE_T(q, step, offset) co_f4_add(co_f4_scale(bvh8_bytes(q), (step)), co_f4_splat(offset))
#else
#define BVH8_PLANE_T(q, step, offset) co_f4_fma(bvh8_bytes(q), co_f4_splat(step), co_f4_splat(offset))
#endif

/* The hit-mask bits of four slots (slots 0-3 or 4-7) of a node (its grid `g`, the half's
 * meta word `meta`, the six plane words of the half), as bvh4's BVH4_ENTER decides a lane: entered
 * at least at tmin, before `limit`, the exit widened by a few ulps. */
CO_INLINE uint32_t bvh8_half_hits(const Bvh8Ray* r, const Bvh8Grid* g, uint32_t meta, uint32_t lo_x, uint32_t lo_y,
                                  uint32_t lo_z, uint32_t hi_x, uint32_t hi_y, uint32_t hi_z, float tmin,
                                  float limit, co_float4* inner_enter) {
  co_float4 near_x = BVH8_PLANE_T(r->neg_x ? hi_x : lo_x, g->step.x, g->near.x);
  co_float4 far_x = BVH8_PLANE_T(r->neg_x ? lo_x : hi_x, g->step.x, g->far.x);
  co_float4 near_y = BVH8_PLANE_T(r->neg_y ? hi_y : lo_y, g->step.y, g->near.y);
  co_float4 far_y = BVH8_PLANE_T(r->neg_y ? lo_y : hi_y, g->step.y, g->far.y);
  co_float4 near_z = BVH8_PLANE_T(r->neg_z ? hi_z : lo_z, g->step.z, g->near.z);
  co_float4 far_z = BVH8_PLANE_T(r->neg_z ? lo_z : hi_z, g->step.z, g->far.z);
  co_float4 enter = co_f4_max(co_f4_max(near_x, near_y), co_f4_max(near_z, co_f4_splat(tmin)));
  co_float4 leave = co_f4_min(co_f4_min(far_x, far_y), co_f4_min(far_z, co_f4_splat(limit)));
  uint32_t mask = co_f4_less(enter, co_f4_scale(leave, 1.0000004f));
  /* the four meta bytes at once (the paper's byte-wise form): an inner child (bits 3 and 4 set) has
   * its bit, 24 + slot, moved to its place in the ray's octant order; a leaf its triangles' bits (a
   * unary count in the top 3 bits) at its offset; an unused slot (meta 0) sets nothing */
  uint32_t is_inner4 = meta & (meta << 1) & 0x10101010u;
  uint32_t octant4 = (r->oct_inv * 0x01010101u) & ((is_inner4 >> 4) * 0xffu);
  uint32_t at4 = (meta ^ octant4) & 0x1f1f1f1fu, count4 = (meta >> 5) & 0x07070707u;
  uint32_t bits = 0u;
  for (uint32_t j = 0u; j < 4u; ++j)
    bits |= ((mask >> j) & 1u) ? ((count4 >> (8u * j)) & 7u) << ((at4 >> (8u * j)) & 31u) : 0u;
  uint32_t inner =
      ((is_inner4 >> 4) & 1u) | ((is_inner4 >> 11) & 2u) | ((is_inner4 >> 18) & 4u) | ((is_inner4 >> 25) & 8u);
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
  Bvh8Grid g = bvh8_grid(r, h);
  uint32_t hits = bvh8_half_hits(r, &g, ix.z, q0.x, q0.z, q1.x, q1.z, q2.x, q2.z, tmin, limit, &e0) |
                  bvh8_half_hits(r, &g, ix.w, q0.y, q0.w, q1.y, q1.w, q2.y, q2.w, tmin, limit, &e1);
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
