#include "runtime/render/render_params.h"

#include "runtime/render/scene/camera_params.h"

namespace cohort {

RenderParams make_render_params(const DeviceScene& scene, const SceneCamera& camera, const RenderSettings& s) {
  RenderParams p{};
  p.camera = make_camera_params(camera, s.width, s.height);
  if (s.environment) p.environment = {s.environment->x, s.environment->y, s.environment->z, 0.f};
  p.scene_min = {scene.bounds.lo.x, scene.bounds.lo.y, scene.bounds.lo.z, 0.f};
  p.scene_max = {scene.bounds.hi.x, scene.bounds.hi.y, scene.bounds.hi.z, 0.f};
  p.width = s.width;
  p.height = s.height;
  p.max_depth = s.max_depth;
  p.rr_depth = s.rr_depth;
  p.seed = s.seed;
  p.flags = (s.nee ? RENDER_FLAG_NEE : 0u) | (s.mis ? RENDER_FLAG_MIS : 0u) |
            (s.russian_roulette ? RENDER_FLAG_RUSSIAN_ROULETTE : 0u) |
            (s.environment ? RENDER_FLAG_ENVIRONMENT : 0u);
  if (scene.env_height > 0) p.flags = (p.flags & ~RENDER_FLAG_ENVIRONMENT) | RENDER_FLAG_ENVIRONMENT_MAP;
  p.emitter_count = scene.emitter_count;
  p.emitter_power_total = scene.emitter_power_total;
  p.env_width = scene.env_width;
  p.env_height = scene.env_height;
  p.punctual_count = scene.punctual_count;
  p.pick_triangles = scene.pick.triangles;
  p.pick_environment = scene.pick.environment;
  p.pick_punctual = scene.pick.punctual;
  return p;
}

}  // namespace cohort
