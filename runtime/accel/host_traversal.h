// The device traversal (kernels/common/accel/kdtree_traverse.h) over a tree in host memory: the same code,
// compiled as C++, so a ray replays on the host exactly as a kernel traced it.
#pragma once

#include "kernels/common/accel/bvh4_traverse.h"
#include "kernels/common/accel/bvh8_traverse.h"
#include "kernels/common/accel/bvh8f_traverse.h"
#include "kernels/common/accel/kdtree_traverse.h"
#include "runtime/accel/bvh4.h"
#include "runtime/accel/bvh8.h"
#include "runtime/accel/bvh8f.h"
#include "runtime/accel/kdtree/kdtree.h"

namespace cohort {

inline KdTreeView host_view(const KdTree& tree) {
  KdTreeView view;
  view.nodes = tree.nodes.data();
  view.leaf_triangles = tree.leaf_triangles.data();
  view.triangles = tree.triangles.data();
  view.lo = v3(tree.bounds.lo.x, tree.bounds.lo.y, tree.bounds.lo.z);
  view.hi = v3(tree.bounds.hi.x, tree.bounds.hi.y, tree.bounds.hi.z);
  return view;
}

// The 4-wide BVH (its leaves carry their own copies of the triangles).
inline Bvh4View host_view(const Bvh4& bvh) {
  Bvh4View view;
  view.nodes = bvh.nodes.data();
  view.leaf_triangles = bvh.leaf_vertices.data();
  return view;
}

// The compressed 8-wide BVH (its leaves carry their own copies of the triangles too).
inline Bvh8View host_view(const Bvh8& bvh) {
  Bvh8View view;
  view.nodes = bvh.nodes.data();
  view.leaf_triangles = bvh.leaf_vertices.data();
  return view;
}

// The 8-wide BVH with float planes (its leaves' triangles in blocks of four).
inline Bvh8fView host_view(const Bvh8f& bvh) {
  Bvh8fView view;
  view.nodes = bvh.nodes.data();
  view.leaf_blocks = bvh.leaf_blocks.data();
  return view;
}

}  // namespace cohort
