// Extra EXR channels (the AOVs of render --aov) next to R, G, B, read back by name.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <stdexcept>

#include "runtime/image/image.h"
#include "runtime/util/error.h"

namespace fs = std::filesystem;
using namespace cohort;

namespace {

struct LayerDir {
  fs::path path = fs::temp_directory_path() / ("cohort-layers-" + std::to_string(std::random_device{}()));
  LayerDir() { fs::create_directories(path); }
  ~LayerDir() { fs::remove_all(path); }
};

}  // namespace

TEST(ExrLayers, ChannelsRoundTripByNameNextToTheImage) {
  LayerDir dir;
  Image image(3, 2);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(i) * 0.25f;
  ExrLayer normal{{"N.X", "N.Y", "N.Z"}, {}};
  for (int i = 0; i < 6; ++i) normal.values.insert(normal.values.end(), {float(i), -float(i), 0.5f});
  const float inf = std::numeric_limits<float>::infinity();
  const ExrLayer depth{{"depth.Z"}, {1.f, 2.f, inf, 4.f, 5.f, 6.f}};
  const fs::path file = dir.path / "layers.exr";
  write_exr(file, image, {normal, depth});
  EXPECT_EQ(read_exr(file).rgb, image.rgb);
  EXPECT_EQ(read_exr_channel(file, "N.Y"), (std::vector<float>{0, -1, -2, -3, -4, -5}));
  EXPECT_EQ(read_exr_channel(file, "N.Z"), std::vector<float>(6, 0.5f));
  EXPECT_EQ(read_exr_channel(file, "depth.Z"), depth.values);
  EXPECT_THROW(read_exr_channel(file, "albedo.R"), InputError);
}

TEST(ExrLayers, ALayerOfTheWrongSizeIsRejectedAndNothingIsWritten) {
  LayerDir dir;
  const fs::path file = dir.path / "bad.exr";
  EXPECT_THROW(write_exr(file, Image(2, 2), {ExrLayer{{"depth.Z"}, {1.f, 2.f, 3.f}}}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(file));
}
