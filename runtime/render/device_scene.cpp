#include "runtime/render/device_scene.h"

#include <algorithm>

#include <fmt/format.h>

#include "runtime/cl/cl_error.h"

namespace cohort {
namespace {

co_float4 to_float4(const glm::vec3& v, float w = 0.f) { return co_float4{v.x, v.y, v.z, w}; }

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

// Nodes are breadth-first, so each depth is a contiguous range; walk the tree once to find them.
std::vector<std::uint32_t> level_starts(const KdTree& tree) {
  std::vector<std::uint32_t> depth(tree.nodes.size(), 0);
  std::vector<std::uint32_t> starts{0};
  for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
    if (depth[i] + 1 > starts.size()) starts.push_back(i);
    const KdNode n = tree.nodes[i];
    if (!kd_is_leaf(n)) depth[kd_left_child(n)] = depth[kd_left_child(n) + 1] = depth[i] + 1;
  }
  starts.push_back(static_cast<std::uint32_t>(tree.nodes.size()));
  return starts;
}

std::array<std::vector<float>, 3> centroid_samples(const KdTree& tree) {
  constexpr std::size_t kMaxSamples = 1 << 16;  // quantiles of a 64K sample are plenty for 1K cells
  const std::size_t step = std::max<std::size_t>(1, tree.triangles.size() / kMaxSamples);
  std::array<std::vector<float>, 3> axes;
  for (std::size_t i = 0; i < tree.triangles.size(); i += step) {
    const Triangle& t = tree.triangles[i];
    axes[0].push_back((t.v0.x + t.v1.x + t.v2.x) / 3.f);
    axes[1].push_back((t.v0.y + t.v1.y + t.v2.y) / 3.f);
    axes[2].push_back((t.v0.z + t.v1.z + t.v2.z) / 3.f);
  }
  for (auto& a : axes) std::sort(a.begin(), a.end());
  return axes;
}

}  // namespace

Material to_device_material(const SceneMaterial& m) {
  Material d{};
  d.base_color = to_float4(m.base_color, m.alpha);
  d.emission = to_float4(m.emission);
  d.metallic = m.metallic;
  d.roughness = m.roughness;
  d.transmission = m.transmission;
  d.ior = m.ior;
  d.base_color_texture = m.base_color_texture;
  d.flags = m.double_sided ? MAT_TWO_SIDED_EMISSION : 0u;
  return d;
}

SceneTables make_scene_tables(const Scene& scene, const KdTree& tree) {
  SceneTables t;
  for (const auto& m : scene.materials) t.materials.push_back(to_device_material(m));
  t.triangle_material.reserve(tree.source_index.size());
  for (std::uint32_t src : tree.source_index) t.triangle_material.push_back(scene.material_ids.at(src));
  t.emitters = build_emitter_table(tree, t.materials, t.triangle_material);
  return t;
}

DeviceScene upload_scene(const ClContext& cl, const KdTree& tree, const SceneTables& tables) {
  DeviceScene d;
  d.bytes = bytes_of(tree.nodes) + bytes_of(tree.leaf_triangles) + bytes_of(tree.triangles) +
            bytes_of(tables.triangle_material) + bytes_of(tables.materials) + bytes_of(tables.emitters.entries);
  if (d.bytes > cl.device.global_memory)
    throw DeviceError(fmt::format("the scene needs {} bytes of device memory; {} has {} bytes", d.bytes,
                                  cl.device.name, cl.device.global_memory));
  const auto ro = CL_MEM_READ_ONLY;
  d.nodes = cl.buffer("KD-tree nodes", bytes_of(tree.nodes), tree.nodes.data(), ro);
  d.leaf_triangles = cl.buffer("KD-tree leaf lists", bytes_of(tree.leaf_triangles), tree.leaf_triangles.data(), ro);
  d.triangles = cl.buffer("triangles", bytes_of(tree.triangles), tree.triangles.data(), ro);
  d.triangle_material =
      cl.buffer("triangle materials", bytes_of(tables.triangle_material), tables.triangle_material.data(), ro);
  d.materials = cl.buffer("materials", bytes_of(tables.materials), tables.materials.data(), ro);
  d.emitters = cl.buffer("emitters", bytes_of(tables.emitters.entries), tables.emitters.entries.data(), ro);
  d.emitter_count = static_cast<std::uint32_t>(tables.emitters.entries.size());
  d.emitter_power_total = tables.emitters.total_power;
  d.bounds = tree.bounds;
  d.level_starts = level_starts(tree);
  d.centroid_samples = centroid_samples(tree);
  return d;
}

}  // namespace cohort
