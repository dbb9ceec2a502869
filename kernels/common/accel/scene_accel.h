#ifndef COHORT_SCENE_ACCEL_H
#define COHORT_SCENE_ACCEL_H

#include "common/accel/kdtree_traverse.h"

/* What the rendering and ray-tracing kernels trace with: the KD-tree, or with COHORT_ACCEL_BVH4
 * (the host's --tree bvh4, what --tree auto builds unless a KD-tree is asked for) the 4-wide
 * BVH, which travels in the same buffers. Both give
 * every ray the same hit, so the choice changes speed, never the image. scene_trace_steps has
 * kd_trace_steps' signature. The pth and hash kernels (pth_kernels.h) walk the top of either tree
 * and resume on it. */
#if defined(COHORT_ACCEL_BVH4)
#include "common/accel/bvh4_traverse.h"
typedef Bvh4View SceneAccel;
#define make_scene_accel(nodes, leaf_triangles, triangles, lo, hi) make_bvh4_view(nodes, leaf_triangles)
#define scene_trace_steps bvh4_trace_steps
#else
typedef KdTreeView SceneAccel;
#define make_scene_accel make_tree_view
#define scene_trace_steps kd_trace_steps
#endif

#endif
