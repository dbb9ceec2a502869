/* The partial traversal heuristic on the 4-wide BVH (Wang & Deng, Figure 1, on the tree the
 * renderer traces): a ray's walk down the top `levels` of the tree, the first `top_nodes` nodes
 * (the builder lays the top levels out breadth first, so they are a prefix of the node array that
 * fits local memory). Each step is bvh4_continue's own (the same box test, order and pushes), so the
 * traversal resumed from where the walk stops visits every other node of the full traversal once,
 * in the same order, and finds its hit bit for bit. The walk stops at a leaf, at a node below the
 * top, after `levels` steps, or where the ray enters no child (then it resumes from the top of its
 * stack; with an empty stack the ray has missed everything: *ref = TRAVERSAL_DONE).
 *
 * The record, the ray's PTH bits: per level, the lane (0-3) of the child the walk goes on with,
 * 2 bits a level, the root's most significant; a walk that stops early shifts in zeros, so every
 * key has the same width. Rays with equal bits start their walks through the same subtrees. The
 * record depends on no hit: the walk runs with the ray's full interval. */
#ifndef COHORT_BVH4_PATH_H
#define COHORT_BVH4_PATH_H

#include "common/accel/bvh4_traverse.h"
#include "common/core/contract.h"

/* The lane of `c` that names `ref` (children are distinct). */
CO_INLINE uint32_t bvh4_lane_of(co_uint4 c, uint32_t ref) {
  return ref == c.x ? 0u : ref == c.y ? 1u : ref == c.z ? 2u : 3u;
}

/* bvh4_walk (top in local memory, the kernels) and bvh4_walk_global (the host's gate benchmark and
 * tests, over the whole node array): one body for the two address spaces. */
#define BVH4_DEFINE_WALK(name, SPACE)                                                                            \
  CO_INLINE uint32_t name(const SPACE Bvh4Node* top, uint32_t top_nodes, uint32_t levels, const Bvh4View* bvh,   \
                          const Bvh4Ray* r, float tmin, float tmax, uint32_t* ref, float* ref_t,                 \
                          uint32_t* stack_ref, float* stack_t, int* sp) {                                        \
    co_float4 enter_min = co_f4_splat(tmin);                                                                     \
    uint32_t bits = 0u, level = 0u;                                                                              \
    *ref = 0u;                                                                                                   \
    *ref_t = tmin;                                                                                               \
    *sp = 0;                                                                                                     \
    for (; level < levels && *ref < top_nodes && !bvh4_is_leaf(*ref); ++level) {                                \
      const SPACE Bvh4Node* n = &top[*ref];                                                                      \
      co_float4 enter;                                                                                           \
      uint32_t mask;                                                                                             \
      BVH4_ENTER(&n->lo_x, r, enter_min, tmax * KD_TERMINATION_SLACK, enter, mask);                              \
      if (mask == 0u) {                                                                                          \
        if (*sp == 0) {                                                                                          \
          *ref = TRAVERSAL_DONE;                                                                                 \
        } else {                                                                                                 \
          --*sp;                                                                                                 \
          *ref = stack_ref[*sp];                                                                                 \
          *ref_t = stack_t[*sp];                                                                                 \
        }                                                                                                        \
        break;                                                                                                   \
      }                                                                                                          \
      co_uint4 c = n->child;                                                                                     \
      bvh4_descend(bvh, mask, enter, c, ref, ref_t, stack_ref, stack_t, sp);                                     \
      bits = (bits << 2) | bvh4_lane_of(c, *ref);                                                                \
    }                                                                                                            \
    return levels ? bits << (2u * (levels - level)) : 0u;                                                        \
  }

BVH4_DEFINE_WALK(bvh4_walk, CO_LOCAL)
#if !defined(__OPENCL_VERSION__)
/* CUDA and the host have one address space: the local walk serves the whole array too. */
#define bvh4_walk_global bvh4_walk
#else
BVH4_DEFINE_WALK(bvh4_walk_global, CO_GLOBAL)
#endif

/* The PTH bits alone (the gate benchmark's keys): the walk over the whole tree from the root, with
 * the ray's full interval. */
CO_INLINE uint32_t bvh4_path_bits(const Bvh4View* bvh, co_vec3 org, co_vec3 dir, uint32_t levels) {
  Bvh4Ray r = bvh4_ray(org, dir CO_ALPHA_ARG(0u)); /* a walk tests no triangle: no alpha seed */
  uint32_t stack_ref[BVH4_STACK];
  float stack_t[BVH4_STACK];
  uint32_t ref;
  float ref_t;
  int sp;
  return bvh4_walk_global(bvh->nodes, 0xffffffffu, levels, bvh, &r, 0.0f, INFINITY, &ref, &ref_t, stack_ref, stack_t,
                          &sp);
}

#endif
