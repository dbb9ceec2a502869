#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "runtime/scene/loaders.h"
#include "runtime/scene/ply_body.h"
#include "runtime/scene/ply_header.h"
#include "runtime/scene/scene_builder.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

using ply::Element;
using ply::Property;

// The vertices and fan-triangulated faces of a PLY file, indices not yet checked against the
// vertex count (a file may list its faces first).
struct PlyMesh {
  std::vector<glm::vec3> vertices;
  std::vector<std::uint32_t> corners;  // 3 per triangle
};

int property_index(const Element& e, std::initializer_list<const char*> names, bool list) {
  for (const char* name : names)
    for (std::size_t i = 0; i < e.properties.size(); ++i)
      if (e.properties[i].name == name && e.properties[i].is_list == list) return static_cast<int>(i);
  return -1;
}

template <typename Reader>
class BodyReader {
 public:
  BodyReader(Reader reader, const std::string& file) : in_(std::move(reader)), file_(file) {}

  PlyMesh read(const ply::Header& header) {
    for (const Element& e : header.elements) {
      check_capacity(e);
      if (e.name == "vertex")
        read_vertices(e);
      else if (e.name == "face")
        read_faces(e);
      else
        skip_items(e);
    }
    in_.end_body();
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: {}", file_, what));
  }

  // Before anything is allocated for a header's counts, they must fit in the bytes that are left.
  void check_capacity(const Element& e) const {
    const std::size_t item = Reader::min_item_size(e);
    if (item > 0 && e.count > (in_.remaining() + 1) / item)
      fail(fmt::format("header claims {} '{}' elements but only {} bytes of data remain", e.count, e.name,
                       in_.remaining()));
  }

  void read_vertices(const Element& e) {
    const std::array xyz{property_index(e, {"x"}, false), property_index(e, {"y"}, false),
                         property_index(e, {"z"}, false)};
    if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) fail("vertex element lacks scalar x, y and z properties");
    mesh_.vertices.reserve(static_cast<std::size_t>(e.count));
    for (std::uint64_t v = 0; v < e.count; ++v) {
      in_.begin_item();
      glm::vec3 p(0.f);
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const double value = read_property(e.properties[i]);
        for (int axis = 0; axis < 3; ++axis)
          if (static_cast<int>(i) == xyz[axis]) p[axis] = static_cast<float>(value);
      }
      in_.end_item(e);
      mesh_.vertices.push_back(p);
    }
  }

  void read_faces(const Element& e) {
    const int list = property_index(e, {"vertex_indices", "vertex_index"}, true);
    if (list < 0) fail("face element lacks a vertex_indices list");
    mesh_.corners.reserve(3 * static_cast<std::size_t>(e.count));
    for (std::uint64_t f = 0; f < e.count; ++f) {
      in_.begin_item();
      for (std::size_t i = 0; i < e.properties.size(); ++i)
        if (static_cast<int>(i) == list)
          read_polygon(e.properties[i], f);
        else
          read_property(e.properties[i]);
      in_.end_item(e);
    }
  }

  void read_polygon(const Property& p, std::uint64_t face) {
    const std::size_t n = list_count(p);
    polygon_.clear();
    for (std::size_t k = 0; k < n; ++k) polygon_.push_back(vertex_index(in_.read(p.type), face));
    for (std::size_t k = 1; k + 1 < n; ++k)
      mesh_.corners.insert(mesh_.corners.end(), {polygon_[0], polygon_[k], polygon_[k + 1]});
  }

  std::uint32_t vertex_index(double value, std::uint64_t face) const {
    if (!(value >= 0.0) || value >= static_cast<double>(std::numeric_limits<std::uint32_t>::max()) ||
        value != std::floor(value))
      fail(fmt::format("face {} has invalid vertex index {}", face, value));
    return static_cast<std::uint32_t>(value);
  }

  std::size_t list_count(const Property& p) {
    const double n = in_.read(p.count_type);
    // A list's items must fit in what is left, so a lying count cannot drive an allocation.
    if (!(n >= 0.0) || n != std::floor(n) || n > static_cast<double>(in_.remaining()))
      fail(fmt::format("bad list length {} for property '{}'", n, p.name));
    return static_cast<std::size_t>(n);
  }

  double read_property(const Property& p) {
    if (!p.is_list) return in_.read(p.type);
    const std::size_t n = list_count(p);
    for (std::size_t k = 0; k < n; ++k) in_.read(p.type);
    return 0.0;
  }

  void skip_items(const Element& e) {
    if (e.properties.empty()) return;
    for (std::uint64_t i = 0; i < e.count; ++i) {
      in_.begin_item();
      for (const Property& p : e.properties) read_property(p);
      in_.end_item(e);
    }
  }

  Reader in_;
  const std::string& file_;
  PlyMesh mesh_;
  std::vector<std::uint32_t> polygon_;
};

PlyMesh read_body(const ply::Header& header, const std::string& bytes, const std::string& file) {
  const std::string_view body = std::string_view(bytes).substr(header.body_offset);
  if (header.format == ply::Format::ascii) {
    const std::string_view header_text = std::string_view(bytes).substr(0, header.body_offset);
    const auto first_line = static_cast<std::size_t>(std::count(header_text.begin(), header_text.end(), '\n')) + 1;
    return BodyReader<ply::AsciiReader>(ply::AsciiReader(body, file, first_line), file).read(header);
  }
  const bool big = header.format == ply::Format::binary_big_endian;
  return BodyReader<ply::BinaryReader>(ply::BinaryReader(body, big, file), file).read(header);
}

}  // namespace

Scene load_ply(const std::filesystem::path& path, const std::string& bytes) {
  const std::string file = path.string();
  const ply::Header header = ply::parse_header(bytes, file);
  const PlyMesh mesh = read_body(header, bytes, file);
  Scene scene;
  SceneBuilder builder(scene);
  const std::uint32_t material = builder.default_material();
  builder.reserve(mesh.corners.size() / 3);
  for (std::size_t c = 0; c < mesh.corners.size(); c += 3) {
    const std::array v{mesh.corners[c], mesh.corners[c + 1], mesh.corners[c + 2]};
    for (std::uint32_t i : v)
      if (i >= mesh.vertices.size())
        throw InputError(fmt::format("{}: a face refers to vertex {} but the file has {} vertices", file, i,
                                     mesh.vertices.size()));
    builder.add({mesh.vertices[v[0]], mesh.vertices[v[1]], mesh.vertices[v[2]]}, material);
  }
  return scene;
}

}  // namespace cohort
