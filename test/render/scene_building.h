// Builds small scenes in memory for the render tests.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "runtime/scene/scene.h"

namespace cohort::test {

inline void add_triangle(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, std::uint32_t material) {
  s.positions.insert(s.positions.end(), {a, b, c});
  s.material_ids.push_back(material);
  if (!s.uvs.empty()) s.uvs.insert(s.uvs.end(), 3, glm::vec2(0.f));
}

// A quad o, o + u, o + u + v, o + v (front side: u x v) with texture coordinates (0,0)..(1,1).
inline void add_quad(Scene& s, glm::vec3 o, glm::vec3 u, glm::vec3 v, std::uint32_t material, bool with_uvs = false) {
  const std::size_t first = s.positions.size();
  add_triangle(s, o, o + u, o + u + v, material);
  add_triangle(s, o, o + u + v, o + v, material);
  if (with_uvs) {
    if (s.uvs.empty()) s.uvs.assign(s.positions.size(), glm::vec2(0.f));
    const glm::vec2 t[6] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 6; ++i) s.uvs[first + i] = t[i];
  }
}

}  // namespace cohort::test
