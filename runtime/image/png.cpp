#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <stb/stb_image_write.h>

#include "runtime/image/image.h"
#include "runtime/util/atomic_file.h"

namespace cohort {

float srgb_encode(float linear) {
  const float v = std::clamp(linear, 0.f, 1.f);  // also maps NaN to 0 through the comparisons below
  if (!(v > 0.0031308f)) return v > 0.f ? 12.92f * v : 0.f;
  return 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

void write_png(const std::filesystem::path& path, const Image& image) {
  std::vector<std::uint8_t> bytes(image.rgb.size());
  std::transform(image.rgb.begin(), image.rgb.end(), bytes.begin(), [](float v) {
    return static_cast<std::uint8_t>(std::lround(srgb_encode(v) * 255.f));
  });
  write_atomically(path, [&](const std::filesystem::path& temp) {
    if (!stbi_write_png(temp.c_str(), image.width, image.height, 3, bytes.data(), image.width * 3))
      throw std::runtime_error("cannot write PNG " + temp.string());
  });
}

}  // namespace cohort
