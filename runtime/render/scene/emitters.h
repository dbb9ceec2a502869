// The table NEE picks emissive triangles from, by power.
#pragma once

#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/accel/kdtree/kdtree.h"

namespace cohort {

struct EmitterTable {
  std::vector<EmitterEntry> entries;  // emissive kept triangles, in triangle order
  float total_power = 0;
};

// materials: device materials; triangle_material: per kept triangle of the tree.
EmitterTable build_emitter_table(const KdTree& tree, const std::vector<Material>& materials,
                                 const std::vector<std::uint32_t>& triangle_material);

}  // namespace cohort
