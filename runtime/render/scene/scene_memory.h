// Device memory of a prepared scene, by part: what upload_scene allocates, what `cohort info` and
// `--stats` report per triangle, and what a memory limit is checked against before any upload.
#pragma once

#include <cstddef>
#include <string>

#include "runtime/accel/wide_bvh.h"
#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/render/scene/device_scene.h"

namespace cohort {

struct SceneMemory {
  std::size_t nodes = 0;       // KD-tree nodes, or the 4-wide BVH's
  std::size_t leaf_lists = 0;  // the KD-tree's leaf lists (indices); the BVH's leaf triangles (copies)
  std::size_t triangles = 0;   // vertices for intersection
  std::size_t shading = 0;     // per-triangle materials and texture coordinates, materials,
                               // textures, lights, environment map
  bool leaves_hold_triangles = false;  // the BVH's: describe() says "leaf triangles"
  std::size_t total() const { return nodes + leaf_lists + triangles + shading; }
  std::size_t tree() const { return nodes + leaf_lists + triangles; }
};

// With `bvh`, its nodes and leaf lists stand for the tree's (what upload_scene uploads then).
SceneMemory scene_memory(const KdTree& tree, const SceneTables& tables, WideBvh bvh = {});

// "123.4 MiB: 150.2 bytes per triangle (nodes 60.1, leaf lists 30.0, triangles 48.0, shading
// 12.1)", "leaf triangles" for the BVH's; `triangles` is the kept triangle count.
std::string describe(const SceneMemory& memory, std::size_t triangles);

}  // namespace cohort
