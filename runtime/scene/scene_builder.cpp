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

}  // namespace

void SceneBuilder::reserve(std::size_t triangles) {
  reserve_more(scene_.positions, 3 * triangles);
  reserve_more(scene_.material_ids, triangles);
}

void SceneBuilder::add(const std::array<glm::vec3, 3>& p, std::uint32_t material,
                       const std::optional<std::array<glm::vec2, 3>>& uv) {
  if (uv && scene_.uvs.empty()) scene_.uvs.assign(scene_.positions.size(), glm::vec2(0.f));
  scene_.positions.insert(scene_.positions.end(), p.begin(), p.end());
  scene_.material_ids.push_back(material);
  if (uv)
    scene_.uvs.insert(scene_.uvs.end(), uv->begin(), uv->end());
  else if (!scene_.uvs.empty())
    scene_.uvs.insert(scene_.uvs.end(), 3, glm::vec2(0.f));
}

std::uint32_t SceneBuilder::default_material() {
  if (!default_material_) {
    default_material_ = static_cast<std::uint32_t>(scene_.materials.size());
    scene_.materials.push_back(SceneMaterial{.name = "default"});
  }
  return *default_material_;
}

}  // namespace cohort
