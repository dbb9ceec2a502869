#include "runtime/render/scene/environment_map.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "kernels/common/accel/scene_view.h"
#include "runtime/render/scene/discrete_cdf.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

void append(std::vector<float>& out, const std::vector<float>& cdf) { out.insert(out.end(), cdf.begin(), cdf.end()); }

}  // namespace

EnvironmentMap make_environment_map(const Image& image, const std::filesystem::path& name) {
  if (image.width < 1 || image.height < 2)
    throw InputError(fmt::format("{}: an environment map needs at least 1 x 2 pixels, this one is {} x {}",
                                 name.string(), image.width, image.height));
  if (std::uint64_t(image.width + 1) * std::uint64_t(image.height) > (1u << 28))
    throw InputError(fmt::format("{}: environment map of {} x {} pixels is too large", name.string(), image.width,
                                 image.height));
  EnvironmentMap e;
  e.source = name;
  e.width = static_cast<std::uint32_t>(image.width);
  e.height = static_cast<std::uint32_t>(image.height);
  const std::uint32_t w = e.width, h = e.height;
  e.texels.reserve(std::size_t(w + 1) * h);
  std::vector<double> lum(std::size_t(w + 1) * h);
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x <= w; ++x) {
      const float* p = image.pixel(static_cast<int>(x % w), static_cast<int>(y));
      for (int c = 0; c < 3; ++c)
        if (!(p[c] >= 0.f && p[c] <= std::numeric_limits<float>::max()))
          throw InputError(fmt::format("{}: pixel ({}, {}) has a negative or non-finite value {}", name.string(),
                                       x % w, y, p[c]));
      e.texels.push_back(co_float4{p[0], p[1], p[2], 0.f});
      lum[std::size_t(y) * (w + 1) + x] = luminance(v3(p[0], p[1], p[2]));
    }
  }
  // rows at theta_j = j pi / (H - 1); cells between rows j, j + 1 and columns i, i + 1
  std::vector<double> cos_theta(h);
  for (std::uint32_t j = 0; j < h; ++j) cos_theta[j] = std::cos(M_PI * double(j) / double(h - 1));
  cos_theta[0] = 1;
  cos_theta[h - 1] = -1;
  for (double c : cos_theta) e.tables.push_back(static_cast<float>(c));
  std::vector<double> row_weight(h - 1);
  std::vector<std::vector<double>> cell_weight(h - 1, std::vector<double>(w));
  for (std::uint32_t j = 0; j + 1 < h; ++j) {
    const double band = cos_theta[j] - cos_theta[j + 1];  // solid angle per unit of 2 pi u
    for (std::uint32_t i = 0; i < w; ++i) {
      const std::size_t k = std::size_t(j) * (w + 1) + i;
      const double mean = 0.25 * (lum[k] + lum[k + 1] + lum[k + w + 1] + lum[k + w + 2]);
      cell_weight[j][i] = mean * band;
      row_weight[j] += cell_weight[j][i];
    }
    e.luminance_integral += row_weight[j] * 2 * M_PI / w;
  }
  append(e.tables, discrete_cdf(row_weight));
  for (const auto& row : cell_weight) append(e.tables, discrete_cdf(row));
  return e;
}

EnvironmentMap load_environment_map(const std::filesystem::path& path) {
  return make_environment_map(read_exr(path), path);
}

}  // namespace cohort
