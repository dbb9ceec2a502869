#include "runtime/render/scene/camera_params.h"

#include <cmath>

namespace cohort {

CameraParams make_camera_params(const SceneCamera& camera, std::uint32_t width, std::uint32_t height) {
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  glm::vec3 right = glm::cross(forward, camera.up);
  // looking along `up`: any perpendicular will do
  if (glm::length(right) < 1e-6f) right = glm::cross(forward, std::abs(forward.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1));
  right = glm::normalize(right);
  const glm::vec3 up = glm::cross(right, forward);
  const float tan_half = std::tan(glm::radians(camera.vfov_degrees) * 0.5f);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  CameraParams p{};
  p.eye = {camera.eye.x, camera.eye.y, camera.eye.z, 0.f};
  p.forward = {forward.x, forward.y, forward.z, 0.f};
  p.right = {right.x * tan_half * aspect, right.y * tan_half * aspect, right.z * tan_half * aspect, 0.f};
  p.up = {up.x * tan_half, up.y * tan_half, up.z * tan_half, 0.f};
  return p;
}

}  // namespace cohort
