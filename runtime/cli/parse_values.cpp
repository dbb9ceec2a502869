#include "runtime/cli/parse_values.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "runtime/util/error.h"

namespace cohort {
namespace {

template <class T>
bool parse_number(std::string_view s, T& value) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && ptr == s.data() + s.size();
}

}  // namespace

std::pair<std::uint32_t, std::uint32_t> parse_resolution(const std::string& text) {
  const auto x = text.find('x');
  std::uint32_t w = 0, h = 0;
  if (x == std::string::npos || !parse_number(std::string_view(text).substr(0, x), w) ||
      !parse_number(std::string_view(text).substr(x + 1), h) || w == 0 || h == 0 || w > 16384 || h > 16384)
    throw InputError(fmt::format("--res {}: expected WIDTHxHEIGHT with each between 1 and 16384", text));
  return {w, h};
}

double parse_target_error(const std::string& text) {
  double value = 0;
  if (!parse_number(std::string_view(text), value) || !std::isfinite(value) || value <= 0)
    throw InputError(fmt::format("--target-error {}: expected a number above 0, the relative error at which a tile "
                                 "stops (e.g. 0.05)",
                                 text));
  return value;
}

namespace {

// Comma-separated finite numbers; throws with `expected` in the message otherwise.
std::vector<float> parse_list(const std::string& option, const std::string& text, const char* expected) {
  std::vector<float> values;
  std::string_view rest(text);
  while (true) {
    const auto comma = rest.find(',');
    float v = 0;
    if (!parse_number(rest.substr(0, comma), v) || !std::isfinite(v))
      throw InputError(fmt::format("{} {}: expected {}", option, text, expected));
    values.push_back(v);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return values;
}

}  // namespace

glm::vec3 parse_rgb(const std::string& option, const std::string& text) {
  const auto values = parse_list(option, text, "R,G,B or one value, each finite and >= 0");
  for (float v : values)
    if (v < 0) throw InputError(fmt::format("{} {}: values must be >= 0", option, text));
  if (values.size() == 1) return glm::vec3(values[0]);
  if (values.size() == 3) return {values[0], values[1], values[2]};
  throw InputError(fmt::format("{} {}: expected R,G,B or one value", option, text));
}

}  // namespace cohort

namespace cohort {

std::array<float, 6> parse_six(const std::string& option, const std::string& text) {
  const auto values = parse_list(option, text, "six comma-separated numbers");
  if (values.size() != 6) throw InputError(fmt::format("{} {}: expected six comma-separated numbers", option, text));
  std::array<float, 6> out{};
  std::copy(values.begin(), values.end(), out.begin());
  return out;
}

bool is_environment_map_path(const std::string& text) {
  if (text.size() < 4) return false;
  std::string ext = text.substr(text.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr";
}

}  // namespace cohort
