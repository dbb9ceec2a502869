#include "runtime/scene/tangents.h"

#include <algorithm>
#include <cmath>

namespace cohort {
namespace {

glm::vec3 any_orthogonal(const glm::vec3& n) {
  const glm::vec3 axis = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(glm::cross(n, axis), n));
}

float corner_angle(const glm::vec3& a, const glm::vec3& b) {
  const float la = glm::length(a), lb = glm::length(b);
  if (!(la > 0.f) || !(lb > 0.f)) return 0.f;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.f, 1.f));
}

}  // namespace

std::vector<glm::vec4> generate_tangents(const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals, const std::vector<glm::vec2>& uvs,
                                         std::span<const std::array<std::uint32_t, 3>> triangles) {
  std::vector<glm::vec3> tangent(positions.size(), glm::vec3(0.f)), up(positions.size(), glm::vec3(0.f));
  std::vector<glm::vec3> normal = normals;
  if (normal.size() != positions.size()) {  // flat triangles: their faces' normals, angle-weighted
    normal.assign(positions.size(), glm::vec3(0.f));
    for (const auto& t : triangles) {
      const glm::vec3 p[3] = {positions[t[0]], positions[t[1]], positions[t[2]]};
      const glm::vec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
      if (!(glm::length(face) > 0.f)) continue;
      for (int k = 0; k < 3; ++k)
        normal[t[k]] += corner_angle(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]) * glm::normalize(face);
    }
  }
  for (const auto& t : triangles) {
    const glm::vec3 p[3] = {positions[t[0]], positions[t[1]], positions[t[2]]};
    const glm::vec2 uv[3] = {uvs[t[0]], uvs[t[1]], uvs[t[2]]};
    const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const glm::vec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    const glm::vec3 face = glm::cross(e1, e2);
    if (!(std::fabs(det) > 0.f) || !(glm::length(face) > 0.f)) continue;  // no texture or no area
    const glm::vec3 dp_du = (e1 * d2.y - e2 * d1.y) / det, dp_dv = (e2 * d1.x - e1 * d2.x) / det;
    for (int k = 0; k < 3; ++k) {
      glm::vec3 n = normal[t[k]];
      if (!(glm::length(n) > 0.f)) n = glm::normalize(face);
      const glm::vec3 in_plane = dp_du - n * glm::dot(n, dp_du);
      if (!(glm::length(in_plane) > 0.f)) continue;
      const float w = corner_angle(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
      tangent[t[k]] += w * glm::normalize(in_plane);
      up[t[k]] -= w * dp_dv;  // v grows down the image; the map's +y points up it
    }
  }
  std::vector<glm::vec4> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    glm::vec3 n = normal[i];
    if (!(glm::length(n) > 0.f)) n = glm::vec3(0, 0, 1);
    n = glm::normalize(n);
    glm::vec3 t = tangent[i] - n * glm::dot(n, tangent[i]);
    t = glm::length(t) > 0.f && std::isfinite(t.x + t.y + t.z) ? glm::normalize(t) : any_orthogonal(n);
    out[i] = glm::vec4(t, glm::dot(glm::cross(n, t), up[i]) < 0.f ? -1.f : 1.f);
  }
  return out;
}

}  // namespace cohort
