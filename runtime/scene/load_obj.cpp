#include <algorithm>
#include <array>
#include <cstdint>
#include <istream>
#include <optional>
#include <sstream>
#include <streambuf>

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include "runtime/scene/library_message.h"
#include "runtime/scene/loaders.h"
#include "runtime/scene/obj_materials.h"
#include "runtime/scene/obj_text_check.h"
#include "runtime/scene/scene_builder.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

// Lets tinyobjloader read the text in place; a tens-of-megabytes OBJ is not worth a copy.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(const std::string& text) {
    char* begin = const_cast<char*>(text.data());
    setg(begin, begin, begin + text.size());
  }
};

// Reads faces as polygons and fans them here: tinyobjloader's own triangulation splits quads along
// the shorter diagonal, ear-clips larger polygons (dropping degenerate pieces) and silently skips
// faces with bad indices, so neither counts nor errors would match the file.
class ObjEmitter {
 public:
  ObjEmitter(const tinyobj::attrib_t& attrib, std::size_t file_materials, const std::string& file,
             Scene& scene)
      : attrib_(attrib),
        file_(file),
        scene_(scene),
        builder_(scene),
        vertices_(attrib.vertices.size() / 3),
        texcoords_(attrib.texcoords.size() / 2),
        file_materials_(file_materials) {}

  void emit(const tinyobj::shape_t& shape) {
    const auto& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const std::size_t n = mesh.num_face_vertices[f];
      // num_face_vertices is 8-bit in tinyobjloader: a larger polygon desynchronises the index list.
      if (offset + n > mesh.indices.size())
        throw InputError(
            fmt::format("{}: shape '{}' face {} runs past the index list (polygon with "
                        "more than 255 vertices?)",
                        file_, shape.name, f + 1));
      if (n >= 3)
        emit_polygon(shape, f, offset, n);
      else
        ++degenerate_;
      offset += n;
    }
    if (offset != mesh.indices.size())
      throw InputError(
          fmt::format("{}: shape '{}' has a polygon with more than 255 vertices", file_, shape.name));
  }

  void finish() {
    if (degenerate_ > 0)
      scene_.warnings.push_back(
          fmt::format("{}: {} faces with fewer than 3 vertices skipped", file_, degenerate_));
  }

 private:
  void emit_polygon(const tinyobj::shape_t& shape, std::size_t face, std::size_t offset, std::size_t n) {
    const auto* corners = shape.mesh.indices.data() + offset;
    for (std::size_t k = 0; k < n; ++k) check(corners[k], shape, face);
    const auto& ids = shape.mesh.material_ids;
    const std::uint32_t material = material_id(face < ids.size() ? ids[face] : -1);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const std::array c{corners[0], corners[k], corners[k + 1]};
      builder_.add({position(c[0]), position(c[1]), position(c[2])}, material, uvs(c));
    }
  }

  void check(const tinyobj::index_t& i, const tinyobj::shape_t& shape, std::size_t face) const {
    const bool v_ok = i.vertex_index >= 0 && static_cast<std::size_t>(i.vertex_index) < vertices_;
    const bool t_ok = i.texcoord_index < 0 || static_cast<std::size_t>(i.texcoord_index) < texcoords_;
    if (!v_ok)
      throw InputError(fmt::format("{}: shape '{}' face {}: vertex index {} is out of range ({} vertices)",
                                   file_, shape.name, face + 1, i.vertex_index + 1, vertices_));
    if (!t_ok)
      throw InputError(
          fmt::format("{}: shape '{}' face {}: texture coordinate index {} is out of range "
                      "({} coordinates)",
                      file_, shape.name, face + 1, i.texcoord_index + 1, texcoords_));
  }

  std::uint32_t material_id(int id) {
    if (id < 0 || static_cast<std::size_t>(id) >= file_materials_) return builder_.default_material();
    return static_cast<std::uint32_t>(id);
  }

  glm::vec3 position(const tinyobj::index_t& i) const {
    const auto* v = &attrib_.vertices[3 * static_cast<std::size_t>(i.vertex_index)];
    return {v[0], v[1], v[2]};
  }

  // OBJ puts v = 0 at the bottom of the image; Scene::uvs put it at the top row, as glTF does.
  std::optional<std::array<glm::vec2, 3>> uvs(const std::array<tinyobj::index_t, 3>& c) const {
    if (c[0].texcoord_index < 0 || c[1].texcoord_index < 0 || c[2].texcoord_index < 0) return std::nullopt;
    std::array<glm::vec2, 3> out;
    for (int k = 0; k < 3; ++k) {
      const auto* t = &attrib_.texcoords[2 * static_cast<std::size_t>(c[k].texcoord_index)];
      out[k] = {t[0], 1.f - t[1]};
    }
    return out;
  }

  const tinyobj::attrib_t& attrib_;
  const std::string& file_;
  Scene& scene_;
  SceneBuilder builder_;
  std::size_t vertices_;
  std::size_t texcoords_;
  std::size_t file_materials_;
  std::size_t degenerate_ = 0;
};

// tinyobjloader reads "nan" and "inf" as 0; the strict parse's values take their place, so such
// triangles reach the path that drops non-finite ones instead of rendering somewhere else.
void restore_non_finite(const std::vector<obj::NonFiniteValue>& values, std::vector<tinyobj::real_t>& into) {
  for (const obj::NonFiniteValue& v : values)
    if (v.index < into.size()) into[v.index] = v.value;
}

void add_reader_warnings(const std::string& text, const std::string& file, Scene& scene) {
  // tinyobjloader repeats a warning per offending line; a few say enough.
  constexpr int kMaxWarnings = 5;
  std::istringstream lines(text);
  int count = 0;
  for (std::string line; std::getline(lines, line);) {
    // Exporters write both `d` and `Tr` (d = 1 - Tr, as in every McGuire archive file); `d` wins.
    if (line.empty() || line.find("Both `d` and `Tr`") != std::string::npos) continue;
    if (count++ < kMaxWarnings) scene.warnings.push_back(fmt::format("{}: {}", file, line));
  }
  if (count > kMaxWarnings)
    scene.warnings.push_back(fmt::format("{}: {} more OBJ warnings", file, count - kMaxWarnings));
}

}  // namespace

Scene load_obj(const std::filesystem::path& path, const std::string& text) {
  Scene scene;
  const std::string file = path.string();
  const obj::TextCheck checked = obj::check_obj_text(text, file);
  ViewBuffer buffer(text);
  std::istream in(&buffer);
  obj::MaterialLibraries libraries(path, scene);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &libraries, /*triangulate=*/false,
                        /*default_vcols_fallback=*/false))
    throw InputError(fmt::format("{}: invalid OBJ: {}", file, library_message(err)));
  add_reader_warnings(warn, file, scene);
  if (attrib.vertices.size() != 3 * checked.vertex_lines || attrib.texcoords.size() != 2 * checked.texcoord_lines)
    throw InputError(fmt::format("{}: invalid OBJ: {} vertices and {} texture coordinates read, {} and {} stated",
                                 file, attrib.vertices.size() / 3, attrib.texcoords.size() / 2,
                                 checked.vertex_lines, checked.texcoord_lines));
  restore_non_finite(checked.non_finite_vertices, attrib.vertices);
  restore_non_finite(checked.non_finite_texcoords, attrib.texcoords);
  obj::convert_materials(materials, path, scene);
  ObjEmitter emitter(attrib, materials.size(), file, scene);
  for (const tinyobj::shape_t& shape : shapes) emitter.emit(shape);
  emitter.finish();
  return scene;
}

}  // namespace cohort
