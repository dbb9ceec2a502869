#include "runtime/scene/obj_text_check.h"

#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "runtime/scene/strict_number.h"
#include "runtime/util/error.h"

namespace cohort::obj {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Splits a statement into tokens as tinyobjloader does (spaces and tabs); a '#' token starts a comment.
// `tokens` is reused from line to line: an allocation per line would cost more than the parse.
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  for (std::size_t at = 0; at < line.size();) {
    while (at < line.size() && is_blank(line[at])) ++at;
    std::size_t end = at;
    while (end < line.size() && !is_blank(line[end])) ++end;
    if (end == at) break;
    if (line[at] == '#') break;
    tokens.push_back(line.substr(at, end - at));
    at = end;
  }
}

// The shown part of a bad token: enough to find it, never a whole binary blob.
std::string shown(std::string_view token) {
  constexpr std::size_t kMaxShown = 32;
  return token.size() > kMaxShown ? std::string(token.substr(0, kMaxShown)) + "..." : std::string(token);
}

// Calls `statement(line, line_number)` for each statement; tinyobjloader also ends one at a lone
// '\r' (old Mac line ends).
template <typename F>
void for_each_statement(std::string_view text, F&& statement) {
  std::size_t line_number = 1;
  for (std::size_t at = 0; at < text.size(); ++line_number) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(at, end - at);
    for (std::size_t cr; (cr = line.find('\r')) != std::string_view::npos; line.remove_prefix(cr + 1))
      statement(line.substr(0, cr), line_number);
    statement(line, line_number);
    at = end + 1;
  }
}

class Checker {
 public:
  explicit Checker(const std::string& file) : file_(file) {}

  void statement(std::string_view line, std::size_t line_number) {
    line_ = line_number;
    split_tokens(line, tokens_);
    const std::vector<std::string_view>& t = tokens_;
    if (t.empty()) return;
    if (t[0] == "v") {
      numbers(t, 3, "vertex", &result_.non_finite_vertices, 3 * result_.vertex_lines);
      ++result_.vertex_lines;
    } else if (t[0] == "vt") {
      numbers(t, 1, "texture coordinate", &result_.non_finite_texcoords, 2 * result_.texcoord_lines);
      ++result_.texcoord_lines;
    } else if (t[0] == "vn") {
      numbers(t, 3, "normal", nullptr, 0);
    } else if (t[0] == "f") {
      for (std::size_t i = 1; i < t.size(); ++i) face_corner(t[i]);
    }
  }

  TextCheck take() { return std::move(result_); }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: line {}: {}", file_, line_, what));
  }

  // Statement values; the first `kept` of a v (3) or vt (2) are what tinyobjloader stores.
  void numbers(const std::vector<std::string_view>& t, std::size_t at_least, const char* what,
               std::vector<NonFiniteValue>* non_finite, std::size_t first_index) {
    if (t.size() - 1 < at_least)
      fail(fmt::format("{} has {} numbers, needs at least {}", what, t.size() - 1, at_least));
    const std::size_t kept = t[0] == "v" ? 3 : 2;
    for (std::size_t i = 1; i < t.size(); ++i) {
      const std::optional<double> value = parse_number(t[i]);
      if (!value) fail(fmt::format("'{}' in a {} is not a number", shown(t[i]), what));
      if (non_finite && i - 1 < kept && !std::isfinite(static_cast<float>(*value)))
        non_finite->push_back({first_index + i - 1, static_cast<float>(*value)});
    }
  }

  // v, v/t, v//n or v/t/n; each index a non-zero int (negative counts back from the last).
  void face_corner(std::string_view corner) {
    int fields = 0;
    for (std::size_t at = 0; at <= corner.size(); ++fields) {
      std::size_t slash = corner.find('/', at);
      if (slash == std::string_view::npos) slash = corner.size();
      const std::string_view field = corner.substr(at, slash - at);
      at = slash + 1;
      if (fields >= 3) fail(fmt::format("face corner '{}' has more than three indices", shown(corner)));
      if (field.empty() && fields == 1 && slash < corner.size()) continue;  // v//n
      index(field, corner);
    }
  }

  void index(std::string_view field, std::string_view corner) const {
    const std::optional<long long> value = parse_integer(field);
    // tinyobjloader's atoi would wrap an index past an int into some other, valid one.
    const std::string_view unsigned_part = field.substr(!field.empty() && (field[0] == '-' || field[0] == '+'));
    const bool digits =
        !unsigned_part.empty() && unsigned_part.find_first_not_of("0123456789") == std::string_view::npos;
    const bool too_big =
        digits && (!value || *value > std::numeric_limits<int>::max() || *value < -std::numeric_limits<int>::max());
    if (too_big) fail(fmt::format("face index {} is out of range", shown(field)));
    if (!value) fail(fmt::format("face corner '{}' is not made of integer indices", shown(corner)));
    if (*value == 0) fail(fmt::format("face index 0 in '{}' (OBJ indices start at 1)", shown(corner)));
  }

  const std::string& file_;
  std::size_t line_ = 0;
  std::vector<std::string_view> tokens_;
  TextCheck result_;
};

}  // namespace

TextCheck check_obj_text(std::string_view text, const std::string& file) {
  Checker checker(file);
  for_each_statement(text, [&](std::string_view line, std::size_t number) { checker.statement(line, number); });
  return checker.take();
}

std::string checked_mtl_text(std::string_view text, const std::string& file) {
  std::string out;
  out.reserve(text.size());
  std::vector<std::string_view> t;
  for_each_statement(text, [&](std::string_view line, std::size_t number) {
    split_tokens(line, t);
    const bool colour = !t.empty() && (t[0] == "Kd" || t[0] == "Ke" || t[0] == "Ka" || t[0] == "Ks");
    const bool scalar = !t.empty() && (t[0] == "d" || t[0] == "Tr" || t[0] == "Ns" || t[0] == "Ni");
    std::size_t first = 1;
    // "Ka spectral file.rfl", "Kd xyz x y z" and "d -halo 0.5" are legal forms of these statements.
    if ((colour || scalar) && t.size() > 1 && (t[1] == "spectral" || t[1] == "xyz" || t[1] == "-halo"))
      first = t[1] == "spectral" ? t.size() + 1 : 2;
    if ((!colour && !scalar) || first > t.size()) {
      out.append(line).push_back('\n');
      return;
    }
    const auto fail = [&](const std::string& what) {
      throw InputError(fmt::format("{}: line {}: {}", file, number, what));
    };
    const std::size_t count = t.size() - first;
    if (colour ? count != 1 && count != 3 : count != 1)
      fail(fmt::format("{} has {} numbers, needs {}", t[0], count, colour ? "1 or 3" : "1"));
    for (std::size_t i = first; i < t.size(); ++i) {
      const std::optional<double> value = parse_number(t[i]);
      // tinyobjloader reads "nan" as 0, so here a non-finite value is as wrong as a non-number.
      if (!value || !std::isfinite(*value))
        fail(fmt::format("'{}' in {} is not a finite number", shown(t[i]), std::string(t[0])));
    }
    // "Kd 0.5" is grey (g and b default to r); tinyobjloader would read it as red.
    out.append(line);
    if (colour && count == 1) out.append(" ").append(t[first]).append(" ").append(t[first]);
    out.push_back('\n');
  });
  return out;
}

}  // namespace cohort::obj
