// The header of a PLY file: format, elements and their typed properties.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cohort::ply {

enum class Format { ascii, binary_little_endian, binary_big_endian };
enum class Type { i8, u8, i16, u16, i32, u32, f32, f64 };

struct Property {
  std::string name;
  Type type = Type::f32;  // the item type for a list
  bool is_list = false;
  Type count_type = Type::u8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // first byte after "end_header\n"
};

std::size_t type_size(Type type);

// Throws InputError naming `file` when the header is malformed.
Header parse_header(const std::string& bytes, const std::string& file);

}  // namespace cohort::ply
