#include "runtime/scene/strict_number.h"

#include <charconv>
#include <cstdlib>
#include <string>
#include <system_error>

namespace cohort {
namespace {

// std::from_chars takes no leading '+', which OBJ and PLY writers do emit.
std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
  return token;
}

}  // namespace

std::optional<double> parse_number(std::string_view token) {
  token = without_plus(token);
  if (token.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [stop, ec] = std::from_chars(token.data(), end, value);
  if (stop != end) return std::nullopt;
  if (ec == std::errc::result_out_of_range) return std::strtod(std::string(token).c_str(), nullptr);
  if (ec != std::errc{}) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(std::string_view token) {
  token = without_plus(token);
  long long value = 0;
  const char* end = token.data() + token.size();
  const auto [stop, ec] = std::from_chars(token.data(), end, value);
  if (token.empty() || stop != end || ec != std::errc{}) return std::nullopt;
  return value;
}

}  // namespace cohort
