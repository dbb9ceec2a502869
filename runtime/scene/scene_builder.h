// Appends triangles to a Scene while keeping its per-triangle arrays in step.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "runtime/scene/scene.h"

namespace cohort {

class SceneBuilder {
 public:
  explicit SceneBuilder(Scene& scene) : scene_(scene) {}

  void reserve(std::size_t triangles);
  // uvs are optional per triangle: the first triangle with uvs back-fills zeros for the earlier
  // ones, and triangles without uvs get zeros once any have them.
  void add(const std::array<glm::vec3, 3>& p, std::uint32_t material,
           const std::optional<std::array<glm::vec2, 3>>& uv = std::nullopt);
  // The same for glTF's further vertex attributes: a second coordinate set, vertex colours
  // (triangles without colours get white once any have them), normals and tangents (zeros: none).
  struct Attributes {
    std::optional<std::array<glm::vec2, 3>> uv, uv1;
    std::optional<std::array<glm::vec4, 3>> color;
    std::optional<std::array<glm::vec3, 3>> normal;
    std::optional<std::array<glm::vec4, 3>> tangent;
  };
  void add(const std::array<glm::vec3, 3>& p, std::uint32_t material, const Attributes& a);
  // The index of the shared "default" material, appended on first use.
  std::uint32_t default_material();

 private:
  Scene& scene_;
  std::optional<std::uint32_t> default_material_;
};

}  // namespace cohort
