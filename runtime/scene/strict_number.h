// Whole-token number parsing for the text formats (OBJ, ASCII PLY): a token is a number only when
// every character of it belongs to the number, so "1.5abc" or "0x10" is an error rather than 1.5 or 0.
#pragma once

#include <optional>
#include <string_view>

namespace cohort {

// The value of a decimal token ("-1", "+.5", "1e-3", "nan", "inf"), or nullopt when any part of the
// token is not a number. A value beyond double's range is infinite (or zero for a tiny one), so
// the non-finite path that drops triangles sees it.
std::optional<double> parse_number(std::string_view token);

// The value of an integer token ("-12", "+3"), or nullopt when the token is not an integer or
// does not fit in a long long.
std::optional<long long> parse_integer(std::string_view token);

}  // namespace cohort
