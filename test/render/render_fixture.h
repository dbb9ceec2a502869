// Renders shipped scenes on the default OpenCL device (PoCL in CI) for the tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "runtime/cl/context.h"
#include "runtime/backend/program_cache.h"
#include "runtime/render/scene/prepared_scene.h"
#include "runtime/render/renderer.h"

namespace cohort::test {

inline std::filesystem::path shipped_scene(const std::string& name) {
  return std::filesystem::path(COHORT_SOURCE_DIR) / "scenes" / name;
}

// A constant sky of 1 and unbounded paths at size x size and spp: a convex object under the sky
// sends every path back to the sky, so a furnace reads the object's albedo.
inline RenderSettings unbounded_white_sky(std::uint32_t size, std::uint32_t spp) {
  RenderSettings rs;
  rs.width = rs.height = size;
  rs.spp = spp;
  rs.environment = glm::vec3(1.f);
  rs.max_depth = 0;
  return rs;
}

inline RenderResult render_prepared(const PreparedScene& prepared, const RenderSettings& settings) {
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, prepared.tree, prepared.tables);
  return render(cl, cache, scene, prepared.camera, settings);
}

inline RenderResult render_scene(const std::filesystem::path& path, const RenderSettings& settings,
                                 const RenderControl& control = {}) {
  const PreparedScene prepared = prepare_scene(path);
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, prepared.tree, prepared.tables);
  return render(cl, cache, scene, prepared.camera, settings, {}, control);
}

// Mean over pixels and the standard error of that mean, from the spread of per-pixel estimates
// (each pixel is an independent estimate of the same value in the furnace).
struct PixelStats {
  double mean = 0;
  double standard_error = 0;
};

inline PixelStats channel_stats(const Image& image, int channel) {
  const std::size_t n = image.rgb.size() / 3;
  double sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = image.rgb[3 * i + channel];
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  const double variance = std::max(0.0, (sum2 / n - mean * mean) * n / (n - 1));
  return {mean, std::sqrt(variance / n)};
}

// The image's mean in one channel.
inline double mean_of(const Image& image, int channel = 0) { return channel_stats(image, channel).mean; }

// Mean difference (a - b) over a block of pixels of one channel, with the standard error of that
// mean from the per-pixel spread of the difference (pixels are independent estimates), and the
// mean of b there.
struct BlockDifference {
  double mean = 0, standard_error = 0, reference_mean = 0;
};

inline BlockDifference block_difference(const Image& a, const Image& b, int x0, int y0, int w, int h, int channel) {
  double sum = 0, sum2 = 0, ref = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const double d = double(a.pixel(x, y)[channel]) - b.pixel(x, y)[channel];
      sum += d;
      sum2 += d * d;
      ref += b.pixel(x, y)[channel];
    }
  const double n = double(w) * h;
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1)), ref / n};
}

// Two renders of the same expectation agree over the whole image and in 8 x 8 blocks within
// 5 standard errors (plus `slack` of the value).
inline void expect_same_expectation(const Image& a, const Image& b, const std::string& what, double slack = 0) {
  const int blocks = 8, size = a.width / blocks;
  for (int c = 0; c < 3; ++c) {
    const BlockDifference all = block_difference(a, b, 0, 0, a.width, a.height, c);
    EXPECT_LT(std::abs(all.mean), 5 * all.standard_error + slack * all.reference_mean + 1e-6)
        << what << " channel " << c << ": " << all.mean << " of " << all.reference_mean;
    for (int by = 0; by < blocks; ++by)
      for (int bx = 0; bx < blocks; ++bx) {
        const BlockDifference d = block_difference(a, b, bx * size, by * size, size, size, c);
        EXPECT_LT(std::abs(d.mean), 5 * d.standard_error + slack * d.reference_mean + 1e-6)
            << what << " block (" << bx << ", " << by << ") channel " << c << ": " << d.mean << " of " << d.reference_mean;
      }
  }
}

}  // namespace cohort::test
