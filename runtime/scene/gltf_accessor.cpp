#include "runtime/scene/gltf_accessor.h"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "runtime/util/error.h"

namespace cohort::gltf {
namespace {

constexpr std::size_t kMaxZeroAccessor = std::size_t{1} << 26;

// A strided array of `count` elements of `components` values of one component type.
struct View {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int component_type = TINYGLTF_COMPONENT_TYPE_FLOAT;
  int components = 1;
  bool normalized = false;
};

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw InputError(fmt::format("{}: {}", where, what));
}

std::size_t component_size(int component_type, const std::string& where) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      fail(where, fmt::format("unsupported accessor component type {}", component_type));
  }
}

int components_of(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    default:
      return 0;
  }
}

View make_view(const tinygltf::Model& model, int buffer_view, std::size_t byte_offset, std::size_t count,
               int component_type, int components, bool normalized, const std::string& where) {
  View v{
      .count = count, .component_type = component_type, .components = components, .normalized = normalized};
  const std::size_t element = component_size(component_type, where) * components;
  if (count == 0) return v;
  const std::string_view bytes = buffer_view_bytes(model, buffer_view, where);
  const auto& bv = model.bufferViews[static_cast<std::size_t>(buffer_view)];
  v.stride = bv.byteStride ? bv.byteStride : element;
  if (v.stride < element)
    fail(where, fmt::format("buffer view {} byteStride {} is smaller than its {}-byte elements", buffer_view,
                            v.stride, element));
  const bool fits = byte_offset <= bytes.size() && bytes.size() - byte_offset >= element &&
                    (count - 1) <= (bytes.size() - byte_offset - element) / v.stride;
  if (!fits)
    fail(where, fmt::format("accessor of {} elements at byte {} overruns buffer view {} ({} bytes)", count,
                            byte_offset, buffer_view, bytes.size()));
  v.data = reinterpret_cast<const unsigned char*>(bytes.data()) + byte_offset;
  return v;
}

template <typename T>
T load(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

// Normalized integers map to [0, 1] or [-1, 1] as the glTF specification defines.
double component(const View& v, std::size_t i, int c) {
  const unsigned char* p = v.data + i * v.stride;
  switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p + 4 * c);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return load<std::uint32_t>(p + 4 * c);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double x = load<std::uint16_t>(p + 2 * c);
      return v.normalized ? x / 65535.0 : x;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double x = load<std::int16_t>(p + 2 * c);
      return v.normalized ? std::max(x / 32767.0, -1.0) : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double x = p[c];
      return v.normalized ? x / 255.0 : x;
    }
    default: {
      const double x = static_cast<std::int8_t>(p[c]);
      return v.normalized ? std::max(x / 127.0, -1.0) : x;
    }
  }
}

const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index, const std::string& where) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    fail(where, fmt::format("accessor {} does not exist ({} accessors)", index, model.accessors.size()));
  return model.accessors[static_cast<std::size_t>(index)];
}

// Elements of `N` components; sparse accessors start from zeros (or their buffer view) and
// then take their substituted values.
template <int N, typename Out>
std::vector<Out> read_elements(const tinygltf::Model& model, int index, const std::string& where) {
  const auto& a = accessor_at(model, index, where);
  if (components_of(a.type) != N)
    fail(where, fmt::format("accessor {} has type {}, expected {} components", index, a.type, N));
  const View base = a.bufferView >= 0 ? make_view(model, a.bufferView, a.byteOffset, a.count, a.componentType,
                                                  N, a.normalized, where)
                                      : View{.count = 0};
  // With a buffer view, make_view() has checked the count against real bytes; without one the
  // accessor is all zeros and only this cap guards the allocation.
  if (a.bufferView < 0 && a.count > kMaxZeroAccessor)
    fail(where, fmt::format("accessor {} claims {} elements with no buffer view", index, a.count));
  std::vector<Out> out(a.count, Out(0));
  for (std::size_t i = 0; i < base.count; ++i)
    for (int c = 0; c < N; ++c) out[i][c] = static_cast<float>(component(base, i, c));
  if (!a.sparse.isSparse) return out;
  if (a.sparse.count < 0 || a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
    fail(where, fmt::format("sparse accessor {} has a negative count or byte offset", index));
  const auto n = static_cast<std::size_t>(a.sparse.count);
  const int ict = a.sparse.indices.componentType;
  if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(where,
         fmt::format("sparse accessor {} has indices of component type {}, not unsigned integers", index, ict));
  if (n > a.count)
    fail(where, fmt::format("sparse accessor {} substitutes {} of its {} elements", index, n, a.count));
  const View idx = make_view(model, a.sparse.indices.bufferView,
                             static_cast<std::size_t>(a.sparse.indices.byteOffset), n,
                             a.sparse.indices.componentType, 1, false, where);
  const View val = make_view(model, a.sparse.values.bufferView,
                             static_cast<std::size_t>(a.sparse.values.byteOffset), n,
                             a.componentType, N, a.normalized, where);
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(component(idx, k, 0));
    if (i >= out.size())
      fail(where, fmt::format("sparse accessor {} substitutes element {} of {}", index, i, out.size()));
    for (int c = 0; c < N; ++c) out[i][c] = static_cast<float>(component(val, k, c));
  }
  return out;
}

}  // namespace

std::string_view buffer_view_bytes(const tinygltf::Model& model, int buffer_view, const std::string& where) {
  if (buffer_view < 0 || static_cast<std::size_t>(buffer_view) >= model.bufferViews.size())
    fail(where, fmt::format("buffer view {} does not exist ({} buffer views)", buffer_view,
                            model.bufferViews.size()));
  const auto& bv = model.bufferViews[static_cast<std::size_t>(buffer_view)];
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
    fail(where, fmt::format("buffer view {} names buffer {}, which does not exist", buffer_view, bv.buffer));
  const auto& data = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    fail(where, fmt::format("buffer view {} (offset {}, {} bytes) overruns buffer {} ({} bytes)", buffer_view,
                            bv.byteOffset, bv.byteLength, bv.buffer, data.size()));
  return {reinterpret_cast<const char*>(data.data()) + bv.byteOffset, bv.byteLength};
}

std::vector<glm::vec3> read_vec3(const tinygltf::Model& model, int accessor, const std::string& where) {
  return read_elements<3, glm::vec3>(model, accessor, where);
}

std::vector<glm::vec2> read_vec2(const tinygltf::Model& model, int accessor, const std::string& where) {
  return read_elements<2, glm::vec2>(model, accessor, where);
}

std::vector<glm::vec4> read_rgba(const tinygltf::Model& model, int accessor, const std::string& where) {
  if (components_of(accessor_at(model, accessor, where).type) == 4)
    return read_elements<4, glm::vec4>(model, accessor, where);
  std::vector<glm::vec4> out;
  for (const glm::vec3& c : read_elements<3, glm::vec3>(model, accessor, where)) out.emplace_back(c, 1.f);
  return out;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index, const std::string& where) {
  const auto& a = accessor_at(model, index, where);
  const int ct = a.componentType;
  if (components_of(a.type) != 1 ||
      (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    fail(where, fmt::format("index accessor {} is not unsigned byte, short or int scalars", index));
  if (a.sparse.isSparse) fail(where, fmt::format("sparse index accessor {} is not supported", index));
  // Index views are tightly packed by definition; a stride would pick other indices than the writer meant.
  if (a.bufferView >= 0 && static_cast<std::size_t>(a.bufferView) < model.bufferViews.size() &&
      model.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride != 0)
    fail(where, fmt::format("index accessor {} reads buffer view {}, which has a byteStride", index, a.bufferView));
  const View v = make_view(model, a.bufferView, a.byteOffset, a.count, ct, 1, false, where);
  std::vector<std::uint32_t> out(v.count);
  for (std::size_t i = 0; i < v.count; ++i) out[i] = static_cast<std::uint32_t>(component(v, i, 0));
  return out;
}

}  // namespace cohort::gltf
