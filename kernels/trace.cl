/* Traversal only: closest or any hit for a buffer of rays. Used by tests and the ray benchmarks. */
#include "common/kdtree_traverse.h"

__kernel void trace_rays(__global const KdNode* nodes, __global const uint* leaf_triangles,
                         __global const Triangle* triangles, float4 scene_min, float4 scene_max,
                         __global const RayIn* rays, __global HitOut* hits, uint count, uint any_hit) {
  uint i = get_global_id(0);
  if (i >= count) return;
  KdTreeView tree;
  tree.nodes = nodes;
  tree.leaf_triangles = leaf_triangles;
  tree.triangles = triangles;
  tree.lo = v3_from4(scene_min);
  tree.hi = v3_from4(scene_max);
  RayIn r = rays[i];
  hits[i] = kd_trace(&tree, v3_from4(r.origin), v3_from4(r.dir), r.origin.w, r.dir.w, (int)any_hit);
}
