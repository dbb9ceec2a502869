// Linear RGB float images and how they are written: OpenEXR (float) and PNG (sRGB, 8-bit).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace cohort {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // row-major, top row first, 3 floats per pixel

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0.f) {}
  float* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const float* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

// Channels an EXR holds beside R, G, B (an AOV such as albedo.R, albedo.G, albedo.B): `values`
// holds channels.size() floats per pixel, interleaved, top row first.
struct ExrLayer {
  std::vector<std::string> channels;
  std::vector<float> values;
};

// Both writers are atomic: a failed write leaves any earlier file at `path` untouched.
void write_exr(const std::filesystem::path& path, const Image& image, const std::vector<ExrLayer>& layers = {});
void write_png(const std::filesystem::path& path, const Image& image);
Image read_exr(const std::filesystem::path& path);
// One float channel of an EXR by name, top row first; InputError when the file lacks it.
std::vector<float> read_exr_channel(const std::filesystem::path& path, const std::string& channel);

// sRGB transfer function (IEC 61966-2-1) of a linear value, clamped to [0, 1].
float srgb_encode(float linear);

}  // namespace cohort
