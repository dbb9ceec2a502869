// Readers of PLY element data: a token stream for ASCII, a byte cursor for binary. Both read one
// scalar of a declared type as a double, which holds every PLY integer type exactly.
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "runtime/scene/ply_header.h"
#include "runtime/util/error.h"

namespace cohort::ply {

class BinaryReader {
 public:
  BinaryReader(std::string_view data, bool big_endian, const std::string& file)
      : data_(data), swap_(big_endian != (std::endian::native == std::endian::big)), file_(file) {}

  std::size_t remaining() const { return data_.size() - at_; }
  // The fewest bytes one item of the element can take (lists may be empty).
  static std::size_t min_item_size(const Element& e) {
    std::size_t bytes = 0;
    for (const Property& p : e.properties) bytes += type_size(p.is_list ? p.count_type : p.type);
    return bytes;
  }

  double read(Type type) {
    const std::size_t n = type_size(type);
    if (remaining() < n) throw InputError(fmt::format("{}: file ends inside the element data", file_));
    unsigned char b[8];
    std::memcpy(b, data_.data() + at_, n);
    at_ += n;
    if (swap_)
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    return decode(type, b);
  }

 private:
  template <typename T>
  static double as(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return static_cast<double>(v);
  }

  static double decode(Type type, const unsigned char* b) {
    switch (type) {
      case Type::i8:
        return as<std::int8_t>(b);
      case Type::u8:
        return as<std::uint8_t>(b);
      case Type::i16:
        return as<std::int16_t>(b);
      case Type::u16:
        return as<std::uint16_t>(b);
      case Type::i32:
        return as<std::int32_t>(b);
      case Type::u32:
        return as<std::uint32_t>(b);
      case Type::f32:
        return as<float>(b);
      case Type::f64:
        return as<double>(b);
    }
    return 0.0;
  }

  std::string_view data_;
  std::size_t at_ = 0;
  bool swap_;
  const std::string& file_;
};

class AsciiReader {
 public:
  AsciiReader(std::string_view data, const std::string& file) : data_(data), file_(file) {}

  std::size_t remaining() const { return data_.size() - at_; }
  // Each value is at least one character and one separator.
  static std::size_t min_item_size(const Element& e) { return 2 * e.properties.size(); }

  double read(Type) {
    while (at_ < data_.size() && is_space(data_[at_])) ++at_;
    if (at_ >= data_.size()) throw InputError(fmt::format("{}: file ends inside the element data", file_));
    double value = 0.0;
    const char* begin = data_.data() + at_;
    const auto [end, ec] = std::from_chars(begin, data_.data() + data_.size(), value);
    if (ec != std::errc{} || (end < data_.data() + data_.size() && !is_space(*end)))
      throw InputError(fmt::format("{}: bad number '{}' in the element data", file_, token_at(begin)));
    at_ = static_cast<std::size_t>(end - data_.data());
    return value;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

  std::string token_at(const char* begin) const {
    const char* stop = begin;
    while (stop < data_.data() + data_.size() && !is_space(*stop) && stop - begin < 32) ++stop;
    return std::string(begin, stop);
  }

  std::string_view data_;
  std::size_t at_ = 0;
  const std::string& file_;
};

}  // namespace cohort::ply
