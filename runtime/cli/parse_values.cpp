#include "runtime/cli/parse_values.h"

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

glm::vec3 parse_rgb(const std::string& option, const std::string& text) {
  std::vector<float> values;
  std::string_view rest(text);
  while (true) {
    const auto comma = rest.find(',');
    float v = 0;
    if (!parse_number(rest.substr(0, comma), v) || !std::isfinite(v) || v < 0)
      throw InputError(fmt::format("{} {}: expected R,G,B or one value, each finite and >= 0", option, text));
    values.push_back(v);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (values.size() == 1) return glm::vec3(values[0]);
  if (values.size() == 3) return {values[0], values[1], values[2]};
  throw InputError(fmt::format("{} {}: expected R,G,B or one value", option, text));
}

}  // namespace cohort
