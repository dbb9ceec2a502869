// Bounds-checked reads of glTF accessors (byteOffset, byteStride, normalized integers, sparse).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace tinygltf {
class Model;
}

namespace cohort::gltf {

// `where` prefixes every error message ("FILE: mesh 'NAME' primitive 0").
std::vector<glm::vec3> read_vec3(const tinygltf::Model& model, int accessor, const std::string& where);
std::vector<glm::vec2> read_vec2(const tinygltf::Model& model, int accessor, const std::string& where);
// VEC4, or VEC3 with 1 as the fourth component (glTF COLOR_0 may be either).
std::vector<glm::vec4> read_rgba(const tinygltf::Model& model, int accessor, const std::string& where);
// SCALAR unsigned byte, short or int indices.
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor, const std::string& where);
// The bytes of a buffer view, checked against its buffer.
std::string_view buffer_view_bytes(const tinygltf::Model& model, int buffer_view, const std::string& where);

}  // namespace cohort::gltf
