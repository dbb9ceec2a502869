#ifndef COHORT_SCENE_ACCEL_H
#define COHORT_SCENE_ACCEL_H

#include "common/accel/kdtree_traverse.h"

/* What the rendering and ray-tracing kernels trace with: the KD-tree, or with COHORT_ACCEL_BVH4
 * (the host's --tree bvh4, what --tree auto builds unless a KD-tree is asked for) the 4-wide
 * BVH, or with COHORT_ACCEL_BVH8 (--tree bvh8) the compressed 8-wide BVH, or with
 * COHORT_ACCEL_BVH8F (--tree bvh8f) the 8-wide BVH with float planes, which travel in the same
 * buffers. All give
 * every ray the same hit, so the choice changes speed, never the image. scene_trace_steps has
 * kd_trace_steps' signature. The pth and hash kernels (pth_kernels.h) walk the top of the KD-tree
 * or the 4-wide BVH and resume on it; the host refuses them on the 8-wide BVHs. */
/* The 8-wide traversal uses the 4-wide one's helpers. Each header is included where both BVHs see
 * it: the host's embedded sources expand a file once, at its first #include, whatever the
 * conditionals around it (runtime/backend/embedded_sources.cpp). */
#if defined(COHORT_ACCEL_BVH4) || defined(COHORT_ACCEL_BVH8) || defined(COHORT_ACCEL_BVH8F)
#include "common/accel/bvh4_traverse.h"
#endif
#if defined(COHORT_ACCEL_BVH8)
#include "common/accel/bvh8_traverse.h"
#endif
#if defined(COHORT_ACCEL_BVH8F)
#include "common/accel/bvh8f_traverse.h"
#endif
#if defined(COHORT_ACCEL_BVH8F)
typedef Bvh8fView SceneAccel;
#define make_scene_accel(nodes, leaf_triangles, triangles, lo, hi) make_bvh8f_view(nodes, leaf_triangles)
#define scene_trace_steps bvh8f_trace_steps
#elif defined(COHORT_ACCEL_BVH8)
typedef Bvh8View SceneAccel;
#define make_scene_accel(nodes, leaf_triangles, triangles, lo, hi) make_bvh8_view(nodes, leaf_triangles)
#define scene_trace_steps bvh8_trace_steps
#elif defined(COHORT_ACCEL_BVH4)
typedef Bvh4View SceneAccel;
#define make_scene_accel(nodes, leaf_triangles, triangles, lo, hi) make_bvh4_view(nodes, leaf_triangles)
#define scene_trace_steps bvh4_trace_steps
#else
typedef KdTreeView SceneAccel;
#define make_scene_accel make_tree_view
#define scene_trace_steps kd_trace_steps
#endif

#endif
