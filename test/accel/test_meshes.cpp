#include "accel/test_meshes.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "runtime/scene/scene.h"

namespace cohort::test {
namespace {

void fan(const std::vector<glm::vec3>& vertices, const std::vector<long>& face,
         std::vector<glm::vec3>& out) {
  for (std::size_t i = 2; i < face.size(); ++i) {
    for (long index : {face[0], face[i - 1], face[i]}) {
      if (index < 0 || static_cast<std::size_t>(index) >= vertices.size()) {
        throw std::runtime_error("face index out of range");
      }
      out.push_back(vertices[static_cast<std::size_t>(index)]);
    }
  }
}

struct PlyHeader {
  std::size_t vertices = 0, faces = 0, vertex_properties = 0;
};

PlyHeader read_ply_header(std::istream& in) {
  PlyHeader h;
  std::string line, element;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") return h;
    if (word == "format") {
      std::string format;
      words >> format;
      if (format != "ascii") throw std::runtime_error("only ASCII PLY is supported here");
    } else if (word == "element") {
      std::size_t count = 0;
      words >> element >> count;
      if (element == "vertex") h.vertices = count;
      if (element == "face") h.faces = count;
    } else if (word == "property" && element == "vertex") {
      ++h.vertex_properties;
    }
  }
  throw std::runtime_error("PLY header without end_header");
}

// "12", "12/3", "12//4", "12/3/4" -> 0-based index; negative indices count back from the end.
long obj_index(const std::string& token, std::size_t vertex_count) {
  const long raw = std::stol(token.substr(0, token.find('/')));
  return raw < 0 ? static_cast<long>(vertex_count) + raw : raw - 1;
}

}  // namespace

std::optional<std::filesystem::path> shared_scenes() {
  const std::filesystem::path path = COHORT_SHARED_SCENES;
  if (!std::filesystem::is_directory(path)) return std::nullopt;
  return path;
}

std::optional<std::vector<glm::vec3>> load_shared(const std::filesystem::path& relative) {
  const auto root = shared_scenes();
  if (!root || !std::filesystem::is_regular_file(*root / relative)) return std::nullopt;
  const std::filesystem::path path = *root / relative;
  try {
    return load_scene(path).positions;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "load_scene failed (%s); using the test-only reader\n", e.what());
  }
  return path.extension() == ".ply" ? read_ascii_ply(path) : read_obj(path);
}

std::vector<glm::vec3> load_shipped(const char* name) {
  const char* root = std::getenv("COHORT_SOURCE_DIR");
  return load_scene(std::filesystem::path(root && *root ? root : COHORT_SOURCE_DIR) / "scenes" / name).positions;
}

std::vector<glm::vec3> read_ascii_ply(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  const PlyHeader header = read_ply_header(in);
  if (header.vertex_properties < 3) throw std::runtime_error("PLY vertices need x y z");
  std::vector<glm::vec3> vertices(header.vertices);
  for (glm::vec3& v : vertices) {
    in >> v.x >> v.y >> v.z;
    float ignored = 0;
    for (std::size_t p = 3; p < header.vertex_properties; ++p) in >> ignored;
  }
  std::vector<glm::vec3> out;
  for (std::size_t f = 0; f < header.faces; ++f) {
    std::size_t n = 0;
    in >> n;
    std::vector<long> face(n);
    for (long& index : face) in >> index;
    fan(vertices, face, out);
  }
  if (!in) throw std::runtime_error("truncated PLY " + path.string());
  return out;
}

std::vector<glm::vec3> read_obj(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  std::vector<glm::vec3> vertices, out;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "v") {
      glm::vec3 v;
      words >> v.x >> v.y >> v.z;
      vertices.push_back(v);
    } else if (keyword == "f") {
      std::vector<long> face;
      for (std::string token; words >> token;) face.push_back(obj_index(token, vertices.size()));
      fan(vertices, face, out);
    }
  }
  return out;
}

std::vector<glm::vec3> random_soup(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  std::uniform_real_distribution<float> log_size(-7.f, -1.f);  // sizes e^-7 .. e^-1
  std::vector<glm::vec3> out;
  out.reserve(3 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3 center(unit(rng), unit(rng), unit(rng));
    float size = std::exp(log_size(rng));
    if (i % 97 == 0) size = 1.f;  // a few large slabs across much of the box
    glm::vec3 v[3];
    for (glm::vec3& p : v) p = center + size * glm::vec3(unit(rng), unit(rng), unit(rng));
    if (i % 13 == 0) {
      // axis-aligned: planar events, and triangles that sit exactly in candidate planes
      const int axis = static_cast<int>(i / 13 % 3);
      for (glm::vec3& p : v) p[axis] = center[axis];
    }
    out.insert(out.end(), {v[0], v[1], v[2]});
  }
  return out;
}

std::vector<glm::vec3> coplanar_grid(std::size_t cells_x, std::size_t cells_y) {
  std::vector<glm::vec3> out;
  out.reserve(6 * cells_x * cells_y);
  for (std::size_t y = 0; y < cells_y; ++y) {
    for (std::size_t x = 0; x < cells_x; ++x) {
      const glm::vec3 a(float(x), float(y), 0.f), b(float(x + 1), float(y), 0.f);
      const glm::vec3 c(float(x + 1), float(y + 1), 0.f), d(float(x), float(y + 1), 0.f);
      out.insert(out.end(), {a, b, c, a, c, d});
    }
  }
  return out;
}

std::vector<glm::vec3> triangle_copies(std::size_t count) {
  const glm::vec3 a(0.1f, 0.2f, 0.3f), b(1.3f, 0.4f, -0.2f), c(0.5f, 1.1f, 0.9f);
  std::vector<glm::vec3> out;
  out.reserve(3 * count);
  for (std::size_t i = 0; i < count; ++i) out.insert(out.end(), {a, b, c});
  return out;
}

}  // namespace cohort::test
