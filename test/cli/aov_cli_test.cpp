// --aov: first-hit albedo, normal and depth as extra EXR channels (docs/decisions.md names), the same
// bits for every method; bad names are exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "cli/cli_helpers.h"
#include "runtime/image/image.h"

namespace fs = std::filesystem;
using cohort_test::CommandResult;
using cohort_test::run;
using cohort_test::TempDir;

namespace {

// A Kd 0.5 plane z = 0 over x, y in [-8, 8] facing +z (its cross products are (0, 0, 256): a
// normal that rounds to nothing), and a speck at z = 8 that only stretches the bounds so that
// --camera-bounds can put the eye at (0, 0, 4).
fs::path write_plane_scene(const fs::path& dir) {
  std::ofstream(dir / "plane.mtl") << "newmtl grey\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir / "plane.obj") << "mtllib plane.mtl\nusemtl grey\n"
                                      "v -8 -8 0\nv 8 -8 0\nv 8 8 0\nv -8 8 0\n"
                                      "v 7 7 8\nv 8 7 8\nv 8 8 8\n"
                                      "f 1 2 3 4\nf 5 6 7\n";
  return dir / "plane.obj";
}

constexpr int kSide = 33;  // odd: the centre pixel's centre is on the optical axis

std::string plane_render(const fs::path& dir, const std::string& camera_bounds, const std::string& out) {
  return "render " + write_plane_scene(dir).string() + " --env 1 --res 33x33 --spp 4 --fov 30 --camera-bounds " +
         camera_bounds + " --aov albedo,normal,depth -o " + (dir / out).string();
}

}  // namespace

TEST(Aov, AlbedoNormalAndDepthOfAPlane) {
  TempDir dir;
  const CommandResult r = run(plane_render(dir.path, "0.5,0.5,0.5,0.5,0.5,0", "plane"));
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path exr = dir.path / "plane.exr";
  for (const char* c : {"albedo.R", "albedo.G", "albedo.B"})
    for (float v : cohort::read_exr_channel(exr, c)) ASSERT_EQ(v, 0.5f) << c;
  for (float v : cohort::read_exr_channel(exr, "N.X")) ASSERT_EQ(v, 0.f);
  for (float v : cohort::read_exr_channel(exr, "N.Y")) ASSERT_EQ(v, 0.f);
  for (float v : cohort::read_exr_channel(exr, "N.Z")) ASSERT_EQ(v, 1.f);
  // the eye is 4 above the plane: the centre pixel's rays (within a quarter degree of the axis)
  // travel 4, the corners' 4 / cos of their angle, and no pixel is nearer than 4
  const std::vector<float> depth = cohort::read_exr_channel(exr, "depth.Z");
  ASSERT_EQ(depth.size(), std::size_t(kSide * kSide));
  EXPECT_NEAR(depth[kSide * kSide / 2], 4.f, 4e-5f);
  const float half = std::tan(15.f * 3.14159265f / 180.f);
  const float corner = 4.f * std::sqrt(1.f + 2.f * half * half);
  EXPECT_NEAR(depth[0], corner, 0.02f * corner);
  for (float d : depth) EXPECT_GE(d, 4.f - 1e-5f);
}

TEST(Aov, EscapedRaysHaveInfiniteDepthAndNoAlbedo) {
  TempDir dir;
  // looking from the eye at (0, 0, 4) up, away from the plane: the centre pixel sees the sky
  const CommandResult r = run(plane_render(dir.path, "0.5,0.5,0.5,0.5,0.5,1", "sky"));
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path exr = dir.path / "sky.exr";
  EXPECT_TRUE(std::isinf(cohort::read_exr_channel(exr, "depth.Z")[kSide * kSide / 2]));
  EXPECT_EQ(cohort::read_exr_channel(exr, "albedo.R")[kSide * kSide / 2], 0.f);
}

TEST(Aov, EveryMethodWritesTheSameBits) {
  TempDir dir;
  const std::string box = cohort_test::shipped_scene("cornell-box.gltf");
  std::vector<std::vector<float>> first;
  const char* channels[] = {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "depth.Z"};
  // the last run: two PoCL devices share the passes (where the platform gives two)
  for (const std::string method : {"naive", "wavefront", "sc+rg", "pth", "two-devices"}) {
    const fs::path out = dir.path / ("box-" + method);
    const std::string how = method == "two-devices" ? "--pass-spp 1 --device all" : "--method " + method;
    const CommandResult r =
        run("render " + box + " --res 24x16 --spp 3 --aov depth,albedo,normal " + how + " -o " + out.string(),
            method == "two-devices" ? "env 'POCL_DEVICES=pthread pthread' " : "");
    ASSERT_EQ(r.code, 0) << method << ": " << r.output;
    std::vector<std::vector<float>> these;
    for (const char* c : channels) these.push_back(cohort::read_exr_channel(out.string() + ".exr", c));
    if (first.empty()) {
      first = these;
      continue;
    }
    for (std::size_t c = 0; c < these.size(); ++c)
      EXPECT_EQ(0, std::memcmp(these[c].data(), first[c].data(), these[c].size() * sizeof(float)))
          << method << " differs from naive in " << channels[c];
  }
  // the box's walls are Lambertian: some albedo, and unit normals where every sample hits
  float albedo_max = 0;
  for (float v : first[0]) albedo_max = std::max(albedo_max, v);
  EXPECT_GT(albedo_max, 0.1f);
}

TEST(Aov, OnlyTheNamedAovsAreWritten) {
  TempDir dir;
  const CommandResult r = run("render " + cohort_test::shipped_scene("cornell-box.gltf") +
                              " --res 8x8 --spp 1 --aov depth -o " + (dir.path / "d").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(cohort::read_exr_channel(dir.path / "d.exr", "depth.Z").size(), 64u);
  EXPECT_THROW(cohort::read_exr_channel(dir.path / "d.exr", "albedo.R"), std::exception);
}

TEST(Aov, UnknownNameIsExitTwoNamingIt) {
  TempDir dir;
  const CommandResult r = run("render " + cohort_test::shipped_scene("cornell-box.gltf") +
                              " --res 8x8 --spp 1 --aov albedo,normals -o " + (dir.path / "bad").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("'normals'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path / "bad.exr"));
}

TEST(Aov, AdaptiveSamplingAveragesEachPixelOverItsOwnSamples) {
  // --target-error stops tiles at different counts; each pixel's AOVs are those of a uniform
  // render with its count (the same camera rays, summed in the same order): the same bits
  TempDir dir;
  const std::string box = cohort_test::shipped_scene("cornell-box.gltf") + " --res 24x16 --seed 4 --aov depth,albedo,normal ";
  const CommandResult adaptive =
      run("render " + box + "--spp 32 --target-error 0.06 -o " + (dir.path / "adaptive").string());
  ASSERT_EQ(adaptive.code, 0) << adaptive.output;
  const fs::path exr = dir.path / "adaptive.exr";
  const std::vector<float> samples = cohort::read_exr_channel(exr, "samples");
  const std::vector<float> depth = cohort::read_exr_channel(exr, "depth.Z");
  const char* channels[] = {"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "depth.Z"};
  std::vector<float> counts_on_the_box;
  for (const float n : std::vector<float>{16, 24, 32}) {
    const fs::path uniform = dir.path / ("uniform-" + std::to_string(int(n)));
    const CommandResult r = run("render " + box + "--spp " + std::to_string(int(n)) + " -o " + uniform.string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* c : channels) {
      const std::vector<float> want = cohort::read_exr_channel(uniform.string() + ".exr", c);
      const std::vector<float> got = cohort::read_exr_channel(exr, c);
      for (std::size_t i = 0; i < got.size(); ++i) {
        if (samples[i] != n) continue;
        ASSERT_EQ(0, std::memcmp(&got[i], &want[i], sizeof(float))) << c << " of pixel " << i << " (" << n << " samples)";
      }
    }
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (samples[i] == n && std::isfinite(depth[i])) {
        counts_on_the_box.push_back(n);
        break;
      }
  }
  EXPECT_GE(counts_on_the_box.size(), 2u) << "pixels on the box stopped at different counts";
}
