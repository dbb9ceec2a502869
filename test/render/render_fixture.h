// Renders shipped scenes on the default OpenCL device (PoCL in CI) for the tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "runtime/cl/context.h"
#include "runtime/cl/program_cache.h"
#include "runtime/render/prepared_scene.h"
#include "runtime/render/renderer.h"

namespace cohort::test {

inline std::filesystem::path shipped_scene(const std::string& name) {
  return std::filesystem::path(COHORT_SOURCE_DIR) / "scenes" / name;
}

inline RenderResult render_scene(const std::filesystem::path& path, const RenderSettings& settings) {
  const PreparedScene prepared = prepare_scene(path);
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, prepared.tree, prepared.tables);
  return render(cl, cache, scene, prepared.camera, settings);
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

}  // namespace cohort::test
