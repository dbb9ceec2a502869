#include "runtime/scene/scene_builder.h"

#include <algorithm>
#include <vector>

namespace cohort {

namespace {

// Reserving exactly what one more mesh needs would reallocate on every call, which makes a scene of
// many instanced meshes quadratic to load; growing at least geometrically keeps it linear.
template <typename T>
void reserve_more(std::vector<T>& v, std::size_t extra) {
  const std::size_t needed = v.size() + extra;
  if (needed > v.capacity()) v.reserve(std::max(needed, 2 * v.capacity()));
}

// Appends a triangle's values of an optional per-vertex attribute: the first triangle that has
// them back-fills `fill` for the earlier ones, and later triangles without them get `fill`.
template <typename T>
void append_attribute(std::vector<T>& values, std::size_t corners_before, const std::optional<std::array<T, 3>>& v,
                      const T& fill) {
  if (v && values.empty()) values.assign(corners_before, fill);
  if (v)
    values.insert(values.end(), v->begin(), v->end());
  else if (!values.empty())
    values.insert(values.end(), 3, fill);
}

}  // namespace

void SceneBuilder::reserve(std::size_t triangles) {
  reserve_more(scene_.positions, 3 * triangles);
  reserve_more(scene_.material_ids, triangles);
}

void SceneBuilder::add(const std::array<glm::vec3, 3>& p, std::uint32_t material,
                       const std::optional<std::array<glm::vec2, 3>>& uv) {
  add(p, material, Attributes{.uv = uv});
}

void SceneBuilder::add(const std::array<glm::vec3, 3>& p, std::uint32_t material, const Attributes& a) {
  const std::size_t corners = scene_.positions.size();
  scene_.positions.insert(scene_.positions.end(), p.begin(), p.end());
  scene_.material_ids.push_back(material);
  append_attribute(scene_.uvs, corners, a.uv, glm::vec2(0.f));
  append_attribute(scene_.uvs1, corners, a.uv1, glm::vec2(0.f));
  append_attribute(scene_.colors, corners, a.color, glm::vec4(1.f));
  append_attribute(scene_.normals, corners, a.normal, glm::vec3(0.f));
  append_attribute(scene_.tangents, corners, a.tangent, glm::vec4(0.f));
}

std::uint32_t SceneBuilder::default_material() {
  if (!default_material_) {
    default_material_ = static_cast<std::uint32_t>(scene_.materials.size());
    scene_.materials.push_back(SceneMaterial{.name = "default"});
  }
  return *default_material_;
}

}  // namespace cohort
