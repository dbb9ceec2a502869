// Readers of PLY element data: a line-by-line token stream for ASCII, a byte cursor for binary. Both
// read one scalar of a declared type as a double, which holds every PLY integer type exactly, and
// both reject data left after the last element the header declares.
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "runtime/scene/ply_header.h"
#include "runtime/scene/strict_number.h"
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

  // Binary items have no separators to check.
  void begin_item() {}
  void end_item(const Element&) {}

  // Bytes after the last element: a header that claims fewer items than the file holds. Padding
  // (zeros or a line end) some writers append is not data.
  void end_body() const {
    const std::string_view rest = data_.substr(at_);
    if (rest.find_first_not_of(std::string_view("\0 \r\n\t", 5)) != std::string_view::npos)
      throw InputError(
          fmt::format("{}: {} bytes after the last element the header declares", file_, rest.size()));
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

// One element item per line, as the PLY format defines; values are parsed whole and by their declared
// type, so a header that lies about the properties shows up on the first line it does not match.
class AsciiReader {
 public:
  // `first_line`: the line number of the body's first line, for messages.
  AsciiReader(std::string_view data, const std::string& file, std::size_t first_line)
      : data_(data), file_(file), line_(first_line) {}

  std::size_t remaining() const { return data_.size() - at_; }
  // Each value is at least one character and one separator.
  static std::size_t min_item_size(const Element& e) { return 2 * e.properties.size(); }

  void begin_item() {
    while (at_ < data_.size() && is_space(data_[at_])) next();
  }

  void end_item(const Element& e) {
    while (at_ < data_.size() && is_blank(data_[at_])) ++at_;
    if (at_ < data_.size() && data_[at_] != '\n')
      fail(fmt::format("more values than the header declares for a '{}' element ('{}')", e.name,
                       token_at(data_.data() + at_)));
  }

  // Whatever follows the last element: a header that claims fewer items than the file holds.
  void end_body() {
    begin_item();
    if (at_ < data_.size())
      fail(fmt::format("data after the last element the header declares ('{}')", token_at(data_.data() + at_)));
  }

  double read(Type type) {
    while (at_ < data_.size() && is_blank(data_[at_])) ++at_;
    if (at_ >= data_.size()) throw InputError(fmt::format("{}: file ends inside the element data", file_));
    if (data_[at_] == '\n') fail("the line ends before the properties the header declares do");
    const char* begin = data_.data() + at_;
    std::size_t end = at_;
    while (end < data_.size() && !is_space(data_[end])) ++end;
    const std::string_view token(begin, end - at_);
    at_ = end;
    if (is_integer(type)) {
      const std::optional<long long> value = parse_integer(token);
      if (!value || !fits(type, *value))
        fail(fmt::format("'{}' is not a {}-byte {} integer", token_at(begin), type_size(type),
                         is_signed(type) ? "signed" : "unsigned"));
      return static_cast<double>(*value);
    }
    const std::optional<double> value = parse_number(token);
    if (!value) fail(fmt::format("bad number '{}'", token_at(begin)));
    return *value;
  }

 private:
  static bool is_blank(char c) { return c == ' ' || c == '\r' || c == '\t'; }
  static bool is_space(char c) { return is_blank(c) || c == '\n'; }

  static bool is_integer(Type t) { return t != Type::f32 && t != Type::f64; }
  static bool is_signed(Type t) { return t == Type::i8 || t == Type::i16 || t == Type::i32; }
  static bool fits(Type t, long long v) {
    const int bits = 8 * static_cast<int>(type_size(t));
    if (is_signed(t)) return v >= -(1LL << (bits - 1)) && v < (1LL << (bits - 1));
    return v >= 0 && v < (1LL << bits);
  }

  void next() {
    if (data_[at_] == '\n') ++line_;
    ++at_;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: line {}: {}", file_, line_, what));
  }

  std::string token_at(const char* begin) const {
    const char* stop = begin;
    while (stop < data_.data() + data_.size() && !is_space(*stop) && stop - begin < 32) ++stop;
    return std::string(begin, stop);
  }

  std::string_view data_;
  std::size_t at_ = 0;
  const std::string& file_;
  std::size_t line_;
};

}  // namespace cohort::ply
