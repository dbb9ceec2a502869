#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

#include "runtime/image/image.h"
#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"

namespace fs = std::filesystem;
using namespace cohort;

namespace {

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cohort-image-" + std::to_string(std::random_device{}()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(Exr, RoundTripsFloatRgbExactly) {
  TempDir dir;
  Image img(7, 5);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = 0.001f * static_cast<float>(i * i) + 1e-7f;
  img.pixel(3, 2)[1] = 12345.678f;  // beyond half range: must survive as float
  write_exr(dir.path / "a.exr", img);
  const Image back = read_exr(dir.path / "a.exr");
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  EXPECT_EQ(back.rgb, img.rgb);
}

TEST(Exr, ReadingGarbageIsAnInputErrorNamingTheFile) {
  TempDir dir;
  write_file_atomically(dir.path / "bad.exr", "not an exr file at all");
  try {
    read_exr(dir.path / "bad.exr");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.exr"), std::string::npos);
  }
}

TEST(Png, SrgbEncoding) {
  EXPECT_FLOAT_EQ(srgb_encode(0.f), 0.f);
  EXPECT_FLOAT_EQ(srgb_encode(1.f), 1.f);
  EXPECT_FLOAT_EQ(srgb_encode(2.f), 1.f);
  EXPECT_FLOAT_EQ(srgb_encode(-1.f), 0.f);
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.04045f, 1e-5f);
  EXPECT_NEAR(srgb_encode(0.5f), 0.735357f, 1e-5f);
  EXPECT_NEAR(srgb_encode(0.18f), 0.461356f, 1e-5f);
}

TEST(Png, WritesAValidPngHeader) {
  TempDir dir;
  Image img(4, 3);
  write_png(dir.path / "a.png", img);
  const std::string bytes = read_all(dir.path / "a.png");
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
}

TEST(AtomicFile, AFailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  TempDir dir;
  const fs::path target = dir.path / "image.exr";
  write_file_atomically(target, "the earlier good file");
  EXPECT_THROW(write_atomically(target,
                                [](const fs::path& temp) {
                                  std::ofstream(temp) << "half of a new fi";
                                  throw std::runtime_error("interrupted");
                                }),
               std::runtime_error);
  EXPECT_EQ(read_all(target), "the earlier good file");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(AtomicFile, ExrWriteIntoAMissingDirectoryFailsWithoutCreatingAnything) {
  TempDir dir;
  EXPECT_ANY_THROW(write_exr(dir.path / "missing" / "a.exr", Image(2, 2)));
  EXPECT_FALSE(fs::exists(dir.path / "missing"));
}
