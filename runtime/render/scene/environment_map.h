// The environment map of `--env FILE.exr`: its radiance grid and the sampling tables NEE uses,
// laid out as kernels/common/shading/environment.h reads them (Mitsuba's envmap convention, bilinear,
// piecewise-constant sampling over the cells of the grid; docs/lights.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/image/image.h"

namespace cohort {

struct EnvironmentMap {
  std::filesystem::path source;
  std::uint32_t width = 0;   // of the image; the grid has width + 1 columns
  std::uint32_t height = 0;  // rows, pole to pole (at least 2)
  std::vector<co_float4> texels;  // (width + 1) x height, rgb; the last column repeats the first
  std::vector<float> tables;      // cos theta per row, marginal cdf, conditional cdfs (environment.h)
  double luminance_integral = 0;  // integral of the luminance over the sphere (W/m^2 per unit area)
};

// Builds the grid and tables from a linear RGB image; `name` names it in errors. Throws
// InputError for an image under 1 x 2 texels or with a negative or non-finite value.
EnvironmentMap make_environment_map(const Image& image, const std::filesystem::path& name);

// Reads an OpenEXR file (its R, G, B channels) and builds the map; InputError names the file.
EnvironmentMap load_environment_map(const std::filesystem::path& path);

}  // namespace cohort
