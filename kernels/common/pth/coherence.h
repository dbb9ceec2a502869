/* The partial traversal heuristic and the coherence code of Wang & Deng, "Mining Effective
 * Parallelism from Hidden Coherence for GPU Based Path Tracing". */
#ifndef COHORT_COHERENCE_H
#define COHORT_COHERENCE_H

#include "common/accel/kdtree_traverse.h"

/* Walks the ray's first descent through the top subtree, nodes [0, subtree_nodes) of the
 * breadth-first node array (all nodes shallower than `levels`), held in local memory. Stops at
 * the first node outside the subtree or at a leaf, leaving the traversal state there for
 * kd_resume. Returns the PTH bits: 2 per level, root level most significant, padded with zeros
 * when the walk ends above `levels` (docs/decisions.md). */
CO_INLINE uint32_t pth_walk(const CO_LOCAL KdNode* subtree, uint32_t subtree_nodes, uint32_t levels, co_vec3 org,
                            co_vec3 dir, co_vec3 inv_dir, uint32_t* node, float* t0, float* t1, KdStackEntry* stack,
                            int* sp) {
  uint32_t bits = 0u, level = 0u;
  int unordered = 0; /* kept in the saved stack's entries: kd_resume reads it from there */
  for (; level < levels && *node < subtree_nodes; ++level) {
    KdNode n = subtree[*node];
    if (kd_is_leaf(n)) break;
    bits = (bits << 2) | kd_inner_step(n, org, dir, inv_dir, node, t0, t1, stack, sp, &unordered);
  }
  return levels ? bits << (2u * (levels - level)) : 0u;
}

/* Spreads the low 10 bits of v so that two zero bits follow each (Morton order in 3-D). */
CO_INLINE uint64_t morton_spread3(uint32_t v) {
  uint64_t x = v & 0x3ffu;
  x = (x | (x << 16)) & (uint64_t)0x30000ff;
  x = (x | (x << 8)) & (uint64_t)0x300f00f;
  x = (x | (x << 4)) & (uint64_t)0x30c30c3;
  x = (x | (x << 2)) & (uint64_t)0x9249249;
  return x;
}

/* Spreads the low 16 bits of v so that one zero bit follows each (Morton order in 2-D). */
CO_INLINE uint32_t morton_spread2(uint32_t v) {
  uint32_t x = v & 0xffffu;
  x = (x | (x << 8)) & 0x00ff00ffu;
  x = (x | (x << 4)) & 0x0f0f0f0fu;
  x = (x | (x << 2)) & 0x33333333u;
  x = (x | (x << 1)) & 0x55555555u;
  return x;
}

CO_INLINE uint32_t quantize(float f, uint32_t bits) {
  float cells = (float)(1u << bits);
  float c = fmin(fmax(f * cells, 0.0f), cells - 1.0f);
  return (uint32_t)c;
}

/* Cell of x among `count` sorted boundaries: the number of boundaries <= x. */
CO_INLINE uint32_t adaptive_cell(const CO_GLOBAL float* bounds, uint32_t count, float x) {
  uint32_t lo = 0u, hi = count;
  while (lo < hi) {
    uint32_t mid = (lo + hi) >> 1;
    if (bounds[mid] <= x) lo = mid + 1u; else hi = mid;
  }
  return lo;
}

/* Cell of p in the uniform grid of `bits` per axis over the scene bounds, in Morton order. */
CO_INLINE uint64_t uniform_cell_hash(const CodeParams* c, co_vec3 p, uint32_t bits) {
  uint32_t cell[3];
  for (uint32_t a = 0u; a < 3u; ++a) {
    float lo = a == 0u ? c->lo.x : (a == 1u ? c->lo.y : c->lo.z);
    float hi = a == 0u ? c->hi.x : (a == 1u ? c->hi.y : c->hi.z);
    cell[a] = quantize((v3_get(p, a) - lo) / fmax(hi - lo, 1e-30f), bits);
  }
  return (morton_spread3(cell[0]) << 2) | (morton_spread3(cell[1]) << 1) | morton_spread3(cell[2]);
}

CO_INLINE uint64_t origin_hash(const CodeParams* c, const CO_GLOBAL float* origin_bounds, co_vec3 org) {
  if (c->origin_bits == 0u) return 0u;
  if (!c->origin_adaptive) return uniform_cell_hash(c, org, c->origin_bits);
  uint32_t cell[3];
  uint32_t per_axis = (1u << c->origin_bits) - 1u;
  for (uint32_t a = 0u; a < 3u; ++a) cell[a] = adaptive_cell(origin_bounds + a * per_axis, per_axis, v3_get(org, a));
  return (morton_spread3(cell[0]) << 2) | (morton_spread3(cell[1]) << 1) | morton_spread3(cell[2]);
}

/* The two-point key's second point (Meister et al., "On Ray Reordering Techniques for Faster GPU
 * Ray Tracing", I3D 2020): where the ray is estimated to end, org + dir * end_t, on the uniform
 * grid. Rays that will hit nearby geometry from nearby origins trace alike. */
CO_INLINE uint64_t end_hash(const CodeParams* c, co_vec3 org, co_vec3 dir, float end_t) {
  if (c->end_bits == 0u) return 0u;
  return uniform_cell_hash(c, v3_madd(org, dir, end_t), c->end_bits);
}

/* Octahedral map of a unit direction to [0,1]^2 (Meyer et al. 2010), a grid on the sphere whose
 * cells have nearly equal solid angle. */
CO_INLINE uint32_t direction_hash(const CodeParams* c, co_vec3 d) {
  if (c->direction_bits == 0u) return 0u;
  float l1 = fabs(d.x) + fabs(d.y) + fabs(d.z);
  float u = d.x / l1, v = d.y / l1;
  if (d.z < 0.0f) {
    float su = u >= 0.0f ? 1.0f : -1.0f, sv = v >= 0.0f ? 1.0f : -1.0f;
    float nu = (1.0f - fabs(v)) * su, nv = (1.0f - fabs(u)) * sv;
    u = nu;
    v = nv;
  }
  uint32_t cu = quantize(0.5f * (u + 1.0f), c->direction_bits);
  uint32_t cv = quantize(0.5f * (v + 1.0f), c->direction_bits);
  return (morton_spread2(cu) << 1) | morton_spread2(cv);
}

/* A ray's estimated distance to its hit, for the two-point key: the length of its path's previous
 * segment (a path's segments in a room are about as long as each other), or where a camera ray
 * (segment 1) leaves the scene box; never past that exit. */
CO_INLINE float estimated_end(uint32_t segment, float previous_t, float box_exit) {
  return segment > 1u ? fmin(previous_t, box_exit) : box_exit;
}

/* `end_t`: the estimated distance to the ray's hit, for the end part (ignored without one). */
CO_INLINE uint64_t coherence_code(const CodeParams* c, const CO_GLOBAL float* origin_bounds, co_vec3 org, co_vec3 dir,
                                  uint32_t pth_bits, float end_t) {
  uint64_t code = origin_hash(c, origin_bounds, org) << c->origin_shift;
  code |= end_hash(c, org, dir, end_t) << c->end_shift;
  code |= (uint64_t)pth_bits << c->pth_shift;
  code |= (uint64_t)direction_hash(c, dir) << c->direction_shift;
  return code;
}

#endif
