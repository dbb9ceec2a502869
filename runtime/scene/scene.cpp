#include "runtime/scene/scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "runtime/scene/gzip_file.h"
#include "runtime/scene/loaders.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

// Device layout sizes (see geometry_bytes()): a triangle is three float4 vertices.
constexpr std::size_t kTriangleBytes = 48;
constexpr std::size_t kMaterialIdBytes = 4;
constexpr std::size_t kMaterialBytes = 80;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The format extension, looking through a trailing ".gz".
std::string format_extension(const std::filesystem::path& path) {
  const std::filesystem::path inner = is_gzip_name(path) ? path.stem() : path;
  return lower(inner.extension().string());
}

Scene read_format(const std::filesystem::path& path, const std::string& ext) {
  if (ext == ".gltf") return load_gltf(path, read_whole_file(path), false);
  if (ext == ".glb") return load_gltf(path, read_whole_file(path), true);
  if (ext == ".obj") return load_obj(path, read_whole_file(path));
  if (ext == ".ply") return load_ply(path, read_whole_file(path));
  throw InputError(
      fmt::format("{}: unknown scene format '{}' (expected .gltf, .glb, .obj or .ply, optionally .gz)",
                  path.string(), ext));
}

bool finite_and_non_negative(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.f && v.y >= 0.f && v.z >= 0.f;
}

// A NaN or infinite factor turns every pixel that sees the material NaN (and an emitter's power NaN
// poisons light sampling everywhere); a negative colour or emission is no physical material.
void check_material(const SceneMaterial& m, std::size_t index, const std::filesystem::path& path) {
  const auto fail = [&](const std::string& what) {
    const std::string name = m.name.empty() ? "" : fmt::format(" '{}'", m.name);
    throw InputError(fmt::format("{}: material {}{}: {}", path.string(), index, name, what));
  };
  if (!finite_and_non_negative(m.base_color))
    fail(fmt::format("base colour ({}, {}, {}) is negative or not finite", m.base_color.x, m.base_color.y,
                     m.base_color.z));
  if (!finite_and_non_negative(m.emission))
    fail(fmt::format("emission ({}, {}, {}) is negative or not finite", m.emission.x, m.emission.y, m.emission.z));
  if (!finite_and_non_negative(m.absorption))
    fail(fmt::format("volume absorption ({}, {}, {}) is negative or not finite", m.absorption.x, m.absorption.y,
                     m.absorption.z));
  for (const auto& [name, value] : {std::pair{"alpha", m.alpha}, std::pair{"metallic", m.metallic},
                                    std::pair{"roughness", m.roughness}, std::pair{"transmission", m.transmission},
                                    std::pair{"ior", m.ior}})
    if (!std::isfinite(value) || value < 0.f) fail(fmt::format("{} {} is negative or not finite", name, value));
  for (const auto& [name, value] : {std::pair{"clearcoat factor", m.clearcoat.factor},
                                    std::pair{"clearcoat roughness", m.clearcoat.roughness}})
    if (!std::isfinite(value) || value < 0.f) fail(fmt::format("{} {} is negative or not finite", name, value));
  if (!std::isfinite(m.clearcoat.normal_scale))
    fail(fmt::format("clearcoat normal scale {} is not finite", m.clearcoat.normal_scale));
  if (!(m.specular.factor >= 0.f && m.specular.factor <= 1.f))
    fail(fmt::format("specular factor {} is outside [0, 1]", m.specular.factor));
  if (!finite_and_non_negative(m.specular.color))
    fail(fmt::format("specular colour ({}, {}, {}) is negative or not finite", m.specular.color.x, m.specular.color.y,
                     m.specular.color.z));
}

void check_loaded(const Scene& scene, const std::filesystem::path& path) {
  if (scene.triangle_count() == 0)
    throw InputError(fmt::format("{}: the scene has no triangles", path.string()));
  if (scene.materials.empty()) throw InputError(fmt::format("{}: the scene has no materials", path.string()));
  for (std::size_t i = 0; i < scene.materials.size(); ++i) check_material(scene.materials[i], i, path);
  const auto bad = std::find_if(scene.material_ids.begin(), scene.material_ids.end(),
                                [&](std::uint32_t id) { return id >= scene.materials.size(); });
  if (bad != scene.material_ids.end())
    throw InputError(fmt::format("{}: triangle {} uses material {} of {}", path.string(),
                                 bad - scene.material_ids.begin(), *bad, scene.materials.size()));
}

}  // namespace

// Triangles with a NaN or infinite corner are dropped by the KD-tree build; they must not stretch the
// bounds either, or the framing camera lands at infinity.
Bounds Scene::bounds() const {
  Bounds b;
  const auto finite = [](const glm::vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  };
  for (std::size_t i = 0; i + 2 < positions.size(); i += 3)
    if (finite(positions[i]) && finite(positions[i + 1]) && finite(positions[i + 2]))
      for (std::size_t k = i; k < i + 3; ++k) b.extend(positions[k]);
  return b;
}

std::size_t Scene::emissive_triangle_count() const {
  return static_cast<std::size_t>(
      std::count_if(material_ids.begin(), material_ids.end(),
                    [&](std::uint32_t id) { return id < materials.size() && materials[id].is_emissive(); }));
}

std::size_t Scene::geometry_bytes() const {
  std::size_t bytes = triangle_count() * (kTriangleBytes + kMaterialIdBytes);
  bytes += (uvs.size() + uvs1.size()) * sizeof(glm::vec2) + (colors.size() + tangents.size()) * sizeof(glm::vec4);
  bytes += normals.size() * sizeof(glm::vec3);
  bytes += materials.size() * kMaterialBytes;
  for (const Texture& t : textures) bytes += t.rgba.size();
  return bytes;
}

Scene load_scene(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(fmt::format("{}: no such file", path.string()));
  Scene scene = read_format(path, format_extension(path));
  scene.source = path;
  check_loaded(scene, path);
  if (scene.emissive_triangle_count() == 0 && scene.lights.empty())
    scene.warnings.push_back("no light: the image will be black unless an environment is set");
  return scene;
}

SceneCamera framing_camera(const Bounds& bounds) {
  SceneCamera camera;
  if (bounds.empty()) return camera;
  const glm::vec3 c = bounds.center();
  camera.eye = c + glm::vec3(0.f, 0.f, bounds.diagonal());
  camera.target = c;
  camera.up = glm::vec3(0.f, 1.f, 0.f);
  camera.vfov_degrees = 45.f;
  return camera;
}

}  // namespace cohort
