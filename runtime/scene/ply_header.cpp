#include "runtime/scene/ply_header.h"

#include <algorithm>
#include <charconv>
#include <optional>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "runtime/util/error.h"

namespace cohort::ply {
namespace {

// Generous for any real header (they are a few hundred bytes) yet keeps a hostile one cheap.
constexpr std::size_t kMaxHeaderLines = 10000;

std::optional<Type> type_named(const std::string& name) {
  if (name == "char" || name == "int8") return Type::i8;
  if (name == "uchar" || name == "uint8") return Type::u8;
  if (name == "short" || name == "int16") return Type::i16;
  if (name == "ushort" || name == "uint16") return Type::u16;
  if (name == "int" || name == "int32") return Type::i32;
  if (name == "uint" || name == "uint32") return Type::u32;
  if (name == "float" || name == "float32") return Type::f32;
  if (name == "double" || name == "float64") return Type::f64;
  return std::nullopt;
}

class HeaderParser {
 public:
  HeaderParser(const std::string& bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  Header parse() {
    if (next_line() != "ply") fail("not a PLY file (no 'ply' magic)");
    for (std::size_t n = 0; n < kMaxHeaderLines; ++n) {
      if (at_ >= bytes_.size()) fail("header has no end_header line");
      std::istringstream tokens(next_line());
      std::string keyword;
      tokens >> keyword;
      if (keyword == "end_header") {
        header_.body_offset = at_;
        if (!has_format_) fail("header has no format line");
        return header_;
      }
      keyword_line(keyword, tokens);
    }
    fail("header is too long");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: {}", file_, what));
  }

  std::string next_line() {
    std::size_t end = bytes_.find('\n', at_);
    if (end == std::string::npos) end = bytes_.size();
    std::string line = bytes_.substr(at_, end - at_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    at_ = std::min(end + 1, bytes_.size());
    return line;
  }

  void keyword_line(const std::string& keyword, std::istringstream& tokens) {
    if (keyword == "format") return format_line(tokens);
    if (keyword == "element") return element_line(tokens);
    if (keyword == "property") return property_line(tokens);
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) return;
    fail(fmt::format("unknown header line '{}'", keyword));
  }

  void format_line(std::istringstream& tokens) {
    std::string name, version;
    tokens >> name >> version;
    if (name == "ascii")
      header_.format = Format::ascii;
    else if (name == "binary_little_endian")
      header_.format = Format::binary_little_endian;
    else if (name == "binary_big_endian")
      header_.format = Format::binary_big_endian;
    else
      fail(fmt::format("unknown PLY format '{}'", name));
    if (version != "1.0") fail(fmt::format("PLY version '{}' (only 1.0 is defined)", version));
    has_format_ = true;
  }

  void element_line(std::istringstream& tokens) {
    Element e;
    std::string count;
    tokens >> e.name >> count;
    const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
    if (e.name.empty() || ec != std::errc{} || end != count.data() + count.size())
      fail(fmt::format("bad element line for '{}' (count '{}')", e.name, count));
    // A second vertex or face element would silently extend the first one's index space.
    for (const Element& earlier : header_.elements)
      if (earlier.name == e.name) fail(fmt::format("element '{}' declared twice", e.name));
    header_.elements.push_back(std::move(e));
  }

  void property_line(std::istringstream& tokens) {
    if (header_.elements.empty()) fail("property before any element");
    Property p;
    std::string type;
    tokens >> type;
    if (type == "list") {
      std::string count_type;
      tokens >> count_type >> type;
      p.is_list = true;
      p.count_type = required_type(count_type);
    }
    p.type = required_type(type);
    tokens >> p.name;
    header_.elements.back().properties.push_back(std::move(p));
  }

  Type required_type(const std::string& name) const {
    const auto t = type_named(name);
    if (!t) fail(fmt::format("unknown property type '{}'", name));
    return *t;
  }

  const std::string& bytes_;
  const std::string& file_;
  std::size_t at_ = 0;
  Header header_;
  bool has_format_ = false;
};

}  // namespace

std::size_t type_size(Type type) {
  switch (type) {
    case Type::i8:
    case Type::u8:
      return 1;
    case Type::i16:
    case Type::u16:
      return 2;
    case Type::i32:
    case Type::u32:
    case Type::f32:
      return 4;
    case Type::f64:
      return 8;
  }
  return 0;
}

Header parse_header(const std::string& bytes, const std::string& file) {
  return HeaderParser(bytes, file).parse();
}

}  // namespace cohort::ply
