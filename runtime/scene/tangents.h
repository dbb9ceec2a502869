// Tangents for normal maps where a glTF primitive has none (docs/bsdf.md, "Normal maps").
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace cohort {

// Per-vertex tangents (xyz unit, w = +-1 the bitangent's sign, glTF's TANGENT) from positions,
// unit normals (empty: each triangle's own) and the texture coordinates the normal map reads. The
// rule of MikkTSpace without its vertex splitting: each triangle's tangent (the direction of
// increasing u) is projected into the tangent plane of each of its corners' normals and added with
// the corner's angle as weight; w makes cross(n, t) * w point the way v decreases (up the image,
// the normal map's +y). A vertex no triangle gives a tangent gets one orthogonal to its normal.
std::vector<glm::vec4> generate_tangents(const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals, const std::vector<glm::vec2>& uvs,
                                         std::span<const std::array<std::uint32_t, 3>> triangles);

}  // namespace cohort
