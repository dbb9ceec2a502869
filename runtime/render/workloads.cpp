#include "runtime/render/workloads.h"

namespace cohort {

void apply_white_sky(PreparedScene& p, RenderSettings& settings) {
  SceneMaterial white;
  white.name = "white-sky albedo 0.5";
  white.base_color = glm::vec3(0.5f);
  p.scene.materials = {white};
  std::fill(p.scene.material_ids.begin(), p.scene.material_ids.end(), 0u);
  p.tables = make_scene_tables(p.scene, p.tree);
  p.camera = framing_camera(p.scene.bounds());
  apply_white_sky_settings(settings);
}

void apply_white_sky_settings(RenderSettings& settings) {
  settings.environment = glm::vec3(1.f);
  settings.max_depth = 5;
  settings.russian_roulette = false;
}

SceneCamera camera_from_bounds(const Bounds& b, const std::array<float, 6>& f, float vfov_degrees) {
  const glm::vec3 extent = b.extent();
  SceneCamera c;
  c.eye = b.lo + glm::vec3(f[0], f[1], f[2]) * extent;
  c.target = b.lo + glm::vec3(f[3], f[4], f[5]) * extent;
  c.up = {0.f, 1.f, 0.f};
  c.vfov_degrees = vfov_degrees;
  return c;
}

}  // namespace cohort
