// Builds small scenes in memory for the render tests.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/render/scene/prepared_scene.h"
#include "runtime/scene/scene.h"

namespace cohort::test {

inline void add_triangle(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, std::uint32_t material) {
  s.positions.insert(s.positions.end(), {a, b, c});
  s.material_ids.push_back(material);
  if (!s.uvs.empty()) s.uvs.insert(s.uvs.end(), 3, glm::vec2(0.f));
  if (!s.uvs1.empty()) s.uvs1.insert(s.uvs1.end(), 3, glm::vec2(0.f));
  if (!s.colors.empty()) s.colors.insert(s.colors.end(), 3, glm::vec4(1.f));
  if (!s.normals.empty()) s.normals.insert(s.normals.end(), 3, glm::vec3(0.f));
  if (!s.tangents.empty()) s.tangents.insert(s.tangents.end(), 3, glm::vec4(0.f));
}

// One texture of w x h texels from a function of (x, y) to RGBA; `srgb` false: linear data.
template <class F>
int add_texture(Scene& s, int w, int h, F texel, TextureSampler sampler = {}, bool srgb = true) {
  Texture t;
  t.name = "generated";
  t.width = w;
  t.height = h;
  t.sampler = sampler;
  t.srgb = srgb;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::array<std::uint8_t, 4> c = texel(x, y);
      t.rgba.insert(t.rgba.end(), c.begin(), c.end());
    }
  s.textures.push_back(std::move(t));
  return static_cast<int>(s.textures.size() - 1);
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

// A closed icosphere (20 * 4^levels flat triangles, shared vertices, so watertight), front faces
// outwards unless `inward`.
inline void add_sphere(Scene& s, glm::vec3 centre, float radius, std::uint32_t material, int levels = 3,
                bool inward = false) {
  const float t = (1.f + std::sqrt(5.f)) / 2.f;
  std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p = glm::normalize(p);
  std::vector<std::array<std::uint32_t, 3>> f = {
      {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6},
      {7, 1, 8},  {3, 9, 4}, {3, 4, 2}, {3, 2, 6},  {3, 6, 8},   {3, 8, 9},   {4, 9, 5}, {2, 4, 11}, {6, 2, 10},
      {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      return mid[key] = static_cast<std::uint32_t>(v.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& tri : f) {
      const std::uint32_t a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], a, c}, {tri[1], b, a}, {tri[2], c, b}, {a, b, c}});
    }
    f = std::move(next);
  }
  for (const auto& tri : f) {
    glm::vec3 a = centre + radius * v[tri[0]], b = centre + radius * v[tri[1]], c = centre + radius * v[tri[2]];
    const bool outward = glm::dot(glm::cross(b - a, c - a), a + b + c - 3.f * centre) > 0.f;
    if (outward == inward) std::swap(b, c);
    add_triangle(s, a, b, c, material);
  }
}

// A scene built in memory, with its KD-tree and device tables, seen from `camera`.
inline PreparedScene prepare(Scene scene, const SceneCamera& camera) {
  PreparedScene p;
  p.scene = std::move(scene);
  p.tree = build_kdtree(p.scene.positions);
  p.tables = make_scene_tables(p.scene, p.tree);
  p.camera = camera;
  return p;
}

}  // namespace cohort::test
