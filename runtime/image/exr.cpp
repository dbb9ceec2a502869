#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <Iex.h>

#include <fmt/format.h>

#include <stdexcept>

#include "runtime/image/image.h"
#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

Imf::FrameBuffer frame_buffer(float* base, int width) {
  Imf::FrameBuffer fb;
  const std::size_t xs = 3 * sizeof(float), ys = xs * static_cast<std::size_t>(width);
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c)
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(base + c), xs, ys));
  return fb;
}

}  // namespace

void write_exr(const std::filesystem::path& path, const Image& image, const std::vector<ExrLayer>& layers) {
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (const ExrLayer& layer : layers)
    if (layer.values.size() != pixels * layer.channels.size())
      throw std::invalid_argument(fmt::format("write_exr: layer {} has {} values for {} pixels and {} channels",
                                              layer.channels.empty() ? "?" : layer.channels[0], layer.values.size(),
                                              pixels, layer.channels.size()));
  write_atomically(path, [&](const std::filesystem::path& temp) {
    Imf::Header header(image.width, image.height);
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    for (const ExrLayer& layer : layers)
      for (const std::string& c : layer.channels) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(temp.c_str(), header);
    Imf::FrameBuffer fb = frame_buffer(const_cast<float*>(image.rgb.data()), image.width);
    for (const ExrLayer& layer : layers) {
      const std::size_t xs = layer.channels.size() * sizeof(float), ys = xs * static_cast<std::size_t>(image.width);
      for (std::size_t c = 0; c < layer.channels.size(); ++c)
        fb.insert(layer.channels[c],
                  Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(layer.values.data()) + c), xs, ys));
    }
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
  });
}

std::vector<float> read_exr_channel(const std::filesystem::path& path, const std::string& channel) {
  try {
    Imf::InputFile file(path.c_str());
    if (!file.header().channels().findChannel(channel))
      throw InputError(fmt::format("{}: no channel {}", path.string(), channel));
    const auto dw = file.header().dataWindow();
    const std::size_t width = dw.max.x - dw.min.x + 1, height = dw.max.y - dw.min.y + 1;
    std::vector<float> values(width * height);
    float* origin = values.data() - (static_cast<std::ptrdiff_t>(dw.min.y) * width + dw.min.x);
    Imf::FrameBuffer fb;
    fb.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(origin), sizeof(float), sizeof(float) * width));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return values;
  } catch (const Iex::BaseExc& e) {
    throw InputError(fmt::format("{}: not a readable OpenEXR image: {}", path.string(), e.what()));
  }
}

Image read_exr(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const auto dw = file.header().dataWindow();
    Image image(dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1);
    // the slice base is offset so that pixel (dw.min.x, dw.min.y) lands at index 0
    float* origin = image.rgb.data() - (static_cast<std::ptrdiff_t>(dw.min.y) * image.width + dw.min.x) * 3;
    file.setFrameBuffer(frame_buffer(origin, image.width));
    file.readPixels(dw.min.y, dw.max.y);
    return image;
  } catch (const Iex::BaseExc& e) {
    throw InputError(fmt::format("{}: not a readable OpenEXR image: {}", path.string(), e.what()));
  }
}

}  // namespace cohort
