#include "runtime/scene/scene_builder.h"

namespace cohort {

void SceneBuilder::reserve(std::size_t triangles) {
  scene_.positions.reserve(scene_.positions.size() + 3 * triangles);
  scene_.material_ids.reserve(scene_.material_ids.size() + triangles);
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
