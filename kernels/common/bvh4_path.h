/* The 4-wide BVH's partial traversal record, the BVH's counterpart of pth_walk's KD-tree bits
 * (Wang & Deng, Figure 1): down the first `levels` inner nodes of a ray's walk from the root, the
 * index (0-3) of the child the ray enters first, 2 bits a level, most significant first; a walk
 * that reaches a leaf or enters no child shifts in zeros, so every key has the same width. Rays with
 * equal bits start their walks through the same subtrees. The box test is bvh4_trace_steps's over
 * (0, infinity): the record does not depend on any hit. */
#ifndef COHORT_BVH4_PATH_H
#define COHORT_BVH4_PATH_H

#include "common/bvh4_traverse.h"

CO_INLINE uint32_t bvh4_path_bits(const Bvh4View* bvh, co_vec3 org, co_vec3 dir, uint32_t levels) {
  co_float4 ox = co_f4_splat(org.x), oy = co_f4_splat(org.y), oz = co_f4_splat(org.z);
  co_float4 ix = co_f4_splat(bvh4_inverse(dir.x)), iy = co_f4_splat(bvh4_inverse(dir.y)),
            iz = co_f4_splat(bvh4_inverse(dir.z));
  int near_x = dir.x < 0.0f ? 1 : 0, near_y = dir.y < 0.0f ? 3 : 2, near_z = dir.z < 0.0f ? 5 : 4;
  uint32_t bits = 0u, ref = 0u;
  int walking = 1;
  for (uint32_t level = 0u; level < levels; ++level) {
    uint32_t lane = 0u;
    if (walking && !bvh4_is_leaf(ref)) {
      const CO_GLOBAL Bvh4Node* n = &bvh->nodes[ref];
      const CO_GLOBAL co_float4* planes = &n->lo_x;
      co_float4 enter = co_f4_max(co_f4_max(co_f4_mul(co_f4_sub(planes[near_x], ox), ix),
                                            co_f4_mul(co_f4_sub(planes[near_y], oy), iy)),
                                  co_f4_max(co_f4_mul(co_f4_sub(planes[near_z], oz), iz), co_f4_splat(0.0f)));
      co_float4 leave = co_f4_min(co_f4_min(co_f4_mul(co_f4_sub(planes[near_x ^ 1], ox), ix),
                                            co_f4_mul(co_f4_sub(planes[near_y ^ 1], oy), iy)),
                                  co_f4_mul(co_f4_sub(planes[near_z ^ 1], oz), iz));
      uint32_t mask = co_f4_less(enter, co_f4_scale(leave, 1.0000004f));
      if (mask != 0u) {
        float best = INFINITY;
        float t[4] = {enter.x, enter.y, enter.z, enter.w};
        uint32_t child[4] = {n->child.x, n->child.y, n->child.z, n->child.w};
        for (uint32_t k = 0u; k < 4u; ++k)
          if (((mask >> k) & 1u) && t[k] < best) { best = t[k]; lane = k; }
        ref = child[lane];
      } else {
        walking = 0;
      }
    } else {
      walking = 0;
    }
    bits = (bits << 2) | lane;
  }
  return bits;
}

#endif
