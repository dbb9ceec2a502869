#include "runtime/bench/mesh_export.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "runtime/util/atomic_file.h"

namespace cohort {

static_assert(sizeof(glm::vec3) == 12, "positions are written as packed floats");
static_assert(std::endian::native == std::endian::little, "write_ply copies little-endian floats");

std::vector<glm::vec3> midpoint_subdivide(std::span<const glm::vec3> positions, unsigned levels) {
  std::vector<glm::vec3> current(positions.begin(), positions.end());
  for (unsigned l = 0; l < levels; ++l) {
    std::vector<glm::vec3> next;
    next.reserve(current.size() * 4);
    for (std::size_t t = 0; t + 2 < current.size(); t += 3) {
      const glm::vec3 a = current[t], b = current[t + 1], c = current[t + 2];
      const glm::vec3 ab = 0.5f * (a + b), bc = 0.5f * (b + c), ca = 0.5f * (c + a);
      for (const glm::vec3& v : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca}) next.push_back(v);
    }
    current = std::move(next);
  }
  return current;
}

std::vector<glm::vec3> copies_along_z(std::span<const glm::vec3> positions, unsigned copies) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (const glm::vec3& p : positions) {
    lo = std::min(lo, p.z);
    hi = std::max(hi, p.z);
  }
  const float step = positions.empty() ? 0.f : 1.05f * (hi - lo);
  std::vector<glm::vec3> out;
  out.reserve(positions.size() * copies);
  for (unsigned c = 0; c < copies; ++c) {
    for (const glm::vec3& p : positions) out.push_back({p.x, p.y, p.z + step * static_cast<float>(c)});
  }
  return out;
}

void write_ply(const std::filesystem::path& path, std::span<const glm::vec3> positions) {
  const std::size_t faces = positions.size() / 3;
  std::string data = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment cohort export: world-space triangles\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      faces * 3, faces);
  const std::size_t header = data.size();
  data.resize(header + faces * 3 * 12 + faces * 13);
  char* p = data.data() + header;
  for (std::size_t i = 0; i < faces * 3; ++i, p += 12) std::memcpy(p, &positions[i], 12);
  for (std::size_t f = 0; f < faces; ++f, p += 13) {
    *p = 3;
    const std::int32_t idx[3] = {std::int32_t(3 * f), std::int32_t(3 * f + 1), std::int32_t(3 * f + 2)};
    std::memcpy(p + 1, idx, 12);
  }
  write_file_atomically(path, data);
}

}  // namespace cohort
