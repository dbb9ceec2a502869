#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>

#include <glm/glm.hpp>

namespace cohort {

// "WxH" with both in 1..16384; throws InputError naming the option otherwise.
std::pair<std::uint32_t, std::uint32_t> parse_resolution(const std::string& text);
// "R,G,B" or one value for all three, each finite and >= 0.
glm::vec3 parse_rgb(const std::string& option, const std::string& text);

// Whether an --env value names an environment map file (it ends in .exr, any case) rather than
// a radiance.
bool is_environment_map_path(const std::string& text);

// --target-error: a finite number above 0.
double parse_target_error(const std::string& text);

// "a,b,c,d,e,f": six finite numbers (fractions for --camera-bounds).
std::array<float, 6> parse_six(const std::string& option, const std::string& text);

}  // namespace cohort
