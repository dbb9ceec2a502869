#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <Iex.h>

#include <fmt/format.h>

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

void write_exr(const std::filesystem::path& path, const Image& image) {
  write_atomically(path, [&](const std::filesystem::path& temp) {
    Imf::Header header(image.width, image.height);
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(temp.c_str(), header);
    file.setFrameBuffer(frame_buffer(const_cast<float*>(image.rgb.data()), image.width));
    file.writePixels(image.height);
  });
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
