#include "runtime/render/device_scene.h"

#include <fmt/format.h>

#include "runtime/cl/cl_error.h"

namespace cohort {
namespace {

co_float4 to_float4(const glm::vec3& v, float w = 0.f) { return co_float4{v.x, v.y, v.z, w}; }

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.size() * sizeof(T);
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
  return d;
}

}  // namespace cohort
