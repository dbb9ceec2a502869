// Test-only geometry for the KD-tree tests: tiny readers for two shared models (there is no scene
// loader to lean on yet) and procedural triangle soups. Every function returns 3 positions per
// triangle, the input format of build_kdtree.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace cohort::test {

// The shared scene folder (COHORT_SHARED_SCENES), when it exists.
std::optional<std::filesystem::path> shared_scenes();

// A model under the shared scene folder through cohort::load_scene; should that throw, through the
// test-only readers below (.ply ASCII, .obj), so a loader regression does not hide KD-tree results.
// nullopt when the folder or the file is missing, so the caller can skip.
std::optional<std::vector<glm::vec3>> load_shared(const std::filesystem::path& relative);

// A scene shipped in the project's scenes/ folder (COHORT_SOURCE_DIR), through cohort::load_scene.
std::vector<glm::vec3> load_shipped(const char* name);

// ASCII PLY with `x y z ...` vertex lines and `n i0 i1 ...` face lines (fan-triangulated).
std::vector<glm::vec3> read_ascii_ply(const std::filesystem::path& path);

// OBJ `v` and `f` lines only; faces fan-triangulated, indices `a`, `a/b`, `a//c`, `a/b/c`, negative
// (relative) indices allowed.
std::vector<glm::vec3> read_obj(const std::filesystem::path& path);

// Random triangles of mixed size in [-1, 1]^3: many small, some medium, a few large slabs, and some
// axis-aligned ones, so the build sees straddling, planar and empty-space cases.
std::vector<glm::vec3> random_soup(std::size_t count, std::uint32_t seed);

// A grid of 2 * cells_x * cells_y triangles in the plane z = 0 over [0, cells_x] x [0, cells_y].
std::vector<glm::vec3> coplanar_grid(std::size_t cells_x, std::size_t cells_y);

// `count` copies of one (non axis-aligned) triangle.
std::vector<glm::vec3> triangle_copies(std::size_t count);

}  // namespace cohort::test
