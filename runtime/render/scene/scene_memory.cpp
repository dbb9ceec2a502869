#include "runtime/render/scene/scene_memory.h"

#include <fmt/format.h>

#include <algorithm>

namespace cohort {

SceneMemory scene_memory(const KdTree& tree, const SceneTables& tables, WideBvh bvh) {
  SceneMemory m;
  const TraversalArrays arrays = traversal_arrays(tree, bvh);
  m.nodes = arrays.node_bytes;
  m.leaf_lists = arrays.leaf_list_bytes;
  m.leaves_hold_triangles = bool(bvh);
  m.triangles = bytes_of(tree.triangles);
  m.shading = bytes_of(tables.triangle_material) + bytes_of(tables.materials) +
              bytes_of(tables.emitters.entries) + bytes_of(tables.triangle_uvs) + bytes_of(tables.triangle_colors) + bytes_of(tables.triangle_frames) +
              bytes_of(tables.material_coats) + bytes_of(tables.material_sheen) + bytes_of(tables.material_specular) +
              bytes_of(tables.textures) + bytes_of(tables.texels) +
              bytes_of(tables.punctual.lights) +
              (tables.environment ? bytes_of(tables.environment->texels) +
                                        bytes_of(tables.environment->tables)
                                  : 0);
  return m;
}

std::string describe(const SceneMemory& m, std::size_t triangles) {
  const double n = static_cast<double>(std::max<std::size_t>(triangles, 1));
  return fmt::format(
      "{:.1f} MiB: {:.1f} bytes per triangle (nodes {:.1f}, {} {:.1f}, triangles {:.1f}, "
      "shading {:.1f})",
      static_cast<double>(m.total()) / 1048576.0, static_cast<double>(m.total()) / n,
      static_cast<double>(m.nodes) / n, m.leaves_hold_triangles ? "leaf triangles" : "leaf lists",
      static_cast<double>(m.leaf_lists) / n,
      static_cast<double>(m.triangles) / n, static_cast<double>(m.shading) / n);
}

}  // namespace cohort
