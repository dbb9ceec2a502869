#include "runtime/scene/gltf_primitive.h"

#include <array>
#include <numeric>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "runtime/scene/gltf_accessor.h"
#include "runtime/scene/tangents.h"
#include "runtime/util/error.h"

namespace cohort::gltf {
namespace {

using Triple = std::array<std::uint32_t, 3>;

// Instancing lets a small file describe any number of triangles; past this many (about 8 GiB of
// triangle soup) the file is hostile or beyond what the renderer can hold.
constexpr std::size_t kMaxTriangles = std::size_t{1} << 27;

std::size_t triangle_count(int mode, std::size_t indices) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return indices / 3;
  return indices >= 3 ? indices - 2 : 0;
}

// Winding follows the glTF specification's definitions of strips and fans.
Triple triangle(int mode, const std::vector<std::uint32_t>& v, std::size_t i) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
  if (mode == TINYGLTF_MODE_TRIANGLE_FAN) return {v[i + 1], v[i + 2], v[0]};
  return i % 2 == 0 ? Triple{v[i], v[i + 1], v[i + 2]} : Triple{v[i], v[i + 2], v[i + 1]};
}

std::vector<glm::vec3> to_world(std::vector<glm::vec3> p, const glm::dmat4& world) {
  for (glm::vec3& v : p) v = glm::vec3(world * glm::dvec4(v, 1.0));
  return p;
}

int accessor_of(const tinygltf::Primitive& p, const char* attribute) {
  const auto it = p.attributes.find(attribute);
  return it == p.attributes.end() ? -1 : it->second;
}

struct Vertices {
  std::vector<glm::vec3> positions;  // world space
  std::vector<glm::vec2> uvs;        // TEXCOORD_0, or empty
  std::vector<glm::vec2> uvs1;       // TEXCOORD_1, or empty
  std::vector<glm::vec4> colors;     // COLOR_0 (linear RGBA), or empty
  std::vector<glm::vec3> normals;    // NORMAL, world space, unit, or empty
  std::vector<glm::vec4> tangents;   // TANGENT, world space, or generated for a normal map, or empty
};

// Normals go through the inverse transpose; tangents are directions of the surface, so through the
// matrix itself, and a mirroring transform flips the bitangent's sign with the cross product.
void normals_to_world(Vertices& v, const glm::dmat4& world) {
  const glm::dmat3 m(world), normal_matrix = glm::transpose(glm::inverse(m));
  const double handedness = glm::determinant(m) < 0.0 ? -1.0 : 1.0;
  auto unit = [](glm::dvec3 d) { return glm::length(d) > 0.0 ? glm::vec3(glm::normalize(d)) : glm::vec3(0.f); };
  for (glm::vec3& n : v.normals) n = unit(normal_matrix * glm::dvec3(n));
  for (glm::vec4& t : v.tangents) t = glm::vec4(unit(m * glm::dvec3(t)), t.w < 0.f ? -handedness : handedness);
}

// An optional attribute, which must have one element per position.
template <typename T, typename Read>
std::vector<T> read_attribute(const tinygltf::Model& model, const tinygltf::Primitive& p, const char* name,
                              std::size_t positions, const std::string& where, Read read) {
  const int accessor = accessor_of(p, name);
  if (accessor < 0) return {};
  std::vector<T> values = read(model, accessor, where);
  if (values.size() != positions)
    throw InputError(
        fmt::format("{}: {} has {} elements but POSITION has {}", where, name, values.size(), positions));
  return values;
}

Vertices read_vertices(const tinygltf::Model& model, const tinygltf::Primitive& p, const glm::dmat4& world,
                       const std::string& where) {
  Vertices v{.positions = to_world(read_vec3(model, accessor_of(p, "POSITION"), where), world)};
  const std::size_t n = v.positions.size();
  v.uvs = read_attribute<glm::vec2>(model, p, "TEXCOORD_0", n, where, read_vec2);
  v.uvs1 = read_attribute<glm::vec2>(model, p, "TEXCOORD_1", n, where, read_vec2);
  v.colors = read_attribute<glm::vec4>(model, p, "COLOR_0", n, where, read_rgba);
  v.normals = read_attribute<glm::vec3>(model, p, "NORMAL", n, where, read_vec3);
  v.tangents = read_attribute<glm::vec4>(model, p, "TANGENT", n, where, read_rgba);
  normals_to_world(v, world);
  return v;
}

template <typename T>
std::optional<std::array<T, 3>> corners(const std::vector<T>& values, const Triple& v) {
  if (values.empty()) return std::nullopt;
  return std::array{values[v[0]], values[v[1]], values[v[2]]};
}

std::vector<std::uint32_t> vertex_indices(const tinygltf::Model& model, const tinygltf::Primitive& p,
                                          std::size_t vertices, const std::string& where) {
  if (p.indices < 0) {
    std::vector<std::uint32_t> all(vertices);
    std::iota(all.begin(), all.end(), 0u);
    return all;
  }
  std::vector<std::uint32_t> idx = read_indices(model, p.indices, where);
  for (std::size_t k = 0; k < idx.size(); ++k)
    if (idx[k] >= vertices)
      throw InputError(fmt::format("{}: index {} at position {} is out of range ({} vertices)", where, idx[k],
                                   k, vertices));
  return idx;
}

// A normal-mapped material (or clearcoat) on a primitive without TANGENT: tangents from its normals and the
// coordinates the map reads (scene/tangents.h), as the glTF specification asks.
void add_generated_tangents(Vertices& v, const Scene& scene, std::uint32_t material, const std::vector<Triple>& triangles) {
  if (!v.tangents.empty() || material >= scene.materials.size()) return;
  const SceneMaterial& m = scene.materials[material];
  if (m.normal_texture < 0 && m.clearcoat.normal_texture < 0) return;
  // the base's map decides the coordinate set where both the base and the clearcoat have one
  const int set = m.normal_texture >= 0 ? m.normal_texcoord : m.clearcoat.normal_texcoord;
  const std::vector<glm::vec2>& uvs = set == 1 ? v.uvs1 : v.uvs;
  if (uvs.empty()) return;
  v.tangents = generate_tangents(v.positions, v.normals, uvs, triangles);
}

}  // namespace

void PrimitiveEmitter::emit_mesh(int mesh, const glm::dmat4& world) {
  if (mesh < 0 || static_cast<std::size_t>(mesh) >= model_.meshes.size())
    throw InputError(
        fmt::format("{}: mesh {} does not exist ({} meshes)", file_, mesh, model_.meshes.size()));
  const tinygltf::Mesh& m = model_.meshes[static_cast<std::size_t>(mesh)];
  for (std::size_t i = 0; i < m.primitives.size(); ++i)
    emit_primitive(m.primitives[i], fmt::format("{}: mesh '{}' ({}) primitive {}", file_, m.name, mesh, i),
                   world);
}

bool PrimitiveEmitter::skipped(const tinygltf::Primitive& p, int mode) {
  if (mode < TINYGLTF_MODE_TRIANGLES) {
    ++skipped_["point or line primitives skipped"];
    return true;
  }
  if (accessor_of(p, "POSITION") < 0) {
    ++skipped_["primitives without POSITION skipped"];
    return true;
  }
  return false;
}

void PrimitiveEmitter::emit_primitive(const tinygltf::Primitive& p, const std::string& where,
                                      const glm::dmat4& world) {
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
    throw InputError(fmt::format("{}: mode {} is not a glTF primitive mode (0-6)", where, mode));
  if (skipped(p, mode)) return;
  Vertices vertices = read_vertices(model_, p, world, where);
  const std::vector<std::uint32_t> idx = vertex_indices(model_, p, vertices.positions.size(), where);
  if (mode == TINYGLTF_MODE_TRIANGLES && idx.size() % 3 != 0)
    ++skipped_["triangle primitives whose index count is not a multiple of 3 (extra indices ignored)"];
  const std::uint32_t material = material_id(p.material, where);
  // A mirroring transform turns counter-clockwise into clockwise; swapping two corners restores it.
  const bool flip = glm::determinant(glm::dmat3(world)) < 0.0;
  const std::size_t n = triangle_count(mode, idx.size());
  if (scene_.triangle_count() + n > kMaxTriangles)
    throw InputError(fmt::format("{}: the scene expands to more than {} triangles", where, kMaxTriangles));
  builder_.reserve(n);
  std::vector<Triple> triangles(n);
  for (std::size_t t = 0; t < n; ++t) {
    triangles[t] = triangle(mode, idx, t);
    if (flip) std::swap(triangles[t][1], triangles[t][2]);
  }
  add_generated_tangents(vertices, scene_, material, triangles);
  const auto& positions = vertices.positions;
  for (const Triple& v : triangles)
    builder_.add({positions[v[0]], positions[v[1]], positions[v[2]]}, material,
                 {.uv = corners(vertices.uvs, v),
                  .uv1 = corners(vertices.uvs1, v),
                  .color = corners(vertices.colors, v),
                  .normal = corners(vertices.normals, v),
                  .tangent = corners(vertices.tangents, v)});
}

std::uint32_t PrimitiveEmitter::material_id(int material, const std::string& where) {
  if (material < 0) return builder_.default_material();
  if (static_cast<std::size_t>(material) >= model_.materials.size())
    throw InputError(fmt::format("{}: material {} does not exist ({} materials)", where, material,
                                 model_.materials.size()));
  return static_cast<std::uint32_t>(material);
}

void PrimitiveEmitter::finish() {
  for (const auto& [reason, count] : skipped_)
    scene_.warnings.push_back(fmt::format("{}: {} {}", file_, count, reason));
}

}  // namespace cohort::gltf
