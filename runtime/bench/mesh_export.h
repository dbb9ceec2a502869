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

// `copies` side by side along z, each shifted by 1.05x the extent of the input along z (instancing,
// flattened into one mesh): the large-scene benchmark's way past 4^levels. An odd count keeps a
// copy in the middle, where the interior view's camera (z fraction 0.5) stays inside a building.
std::vector<glm::vec3> copies_along_z(std::span<const glm::vec3> positions, unsigned copies);

// Binary little-endian PLY, a triangle soup (3 vertices per face), written atomically.
void write_ply(const std::filesystem::path& path, std::span<const glm::vec3> positions);

}  // namespace cohort
