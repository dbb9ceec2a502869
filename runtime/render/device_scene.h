// A scene and its KD-tree uploaded to one device.
#pragma once

#include <CL/opencl.hpp>

#include <array>
#include <cstddef>
#include <vector>

#include "kernels/common/types.h"
#include "runtime/accel/kdtree.h"
#include "runtime/cl/context.h"
#include "runtime/render/emitters.h"
#include "runtime/scene/scene.h"

namespace cohort {

// Host-side device data, testable without a device.
struct SceneTables {
  std::vector<Material> materials;
  std::vector<std::uint32_t> triangle_material;  // per kept triangle
  EmitterTable emitters;
};

Material to_device_material(const SceneMaterial& m);
SceneTables make_scene_tables(const Scene& scene, const KdTree& tree);

struct DeviceScene {
  cl::Buffer nodes, leaf_triangles, triangles, triangle_material, materials, emitters;
  std::uint32_t emitter_count = 0;
  float emitter_power_total = 0;
  Bounds bounds;
  std::size_t bytes = 0;
  // host-side facts the PTH method sizes itself from
  std::vector<std::uint32_t> level_starts;  // first node of each depth, then the node count
  std::array<std::vector<float>, 3> centroid_samples;  // sorted triangle centroids per axis (subsampled)
};

DeviceScene upload_scene(const ClContext& cl, const KdTree& tree, const SceneTables& tables);

}  // namespace cohort
