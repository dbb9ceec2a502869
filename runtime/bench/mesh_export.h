// World-space triangles written out for other renderers (Mitsuba 3) and for the scaling benchmark,
// which subdivides a model to several triangle counts.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace cohort {

// Each level splits every triangle into 4 at its edge midpoints: the surface stays the same and
// the count grows 4x per level. positions: 3 per triangle.
std::vector<glm::vec3> midpoint_subdivide(std::span<const glm::vec3> positions, unsigned levels);

// Binary little-endian PLY, a triangle soup (3 vertices per face), written atomically.
void write_ply(const std::filesystem::path& path, std::span<const glm::vec3> positions);

}  // namespace cohort
