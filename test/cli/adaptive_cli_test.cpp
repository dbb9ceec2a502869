// --target-error (adaptive sampling, runtime/render/run/adaptive.h): tiles that are clean stop and the
// samples go where the image is noisy; the image is the same bits twice, for every method, on
// two devices and after a checkpoint and resume; at an equal sample budget it is closer to a
// converged image than uniform sampling where every tile is noisy; bad values are exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_helpers.h"
#include "runtime/image/image.h"
#include "runtime/render/run/adaptive.h"

using namespace cohort_test;

namespace {

// The Cornell box at a wide field of view: the box fills the middle ~60% of the image, the rest
// is empty background (no environment: every sample there is exactly 0).
std::string wide_box(const fs::path& out, const std::string& extra = "") {
  return "render " + shipped_scene("cornell-box.gltf") + " --res 64x64 --fov 58 --spp 128 --seed 3 --target-error 0.02 " +
         extra + " -o " + out.string();
}

constexpr int kTile = int(cohort::kAdaptiveTile);

// Each tile's sample count (the EXR's `samples` channel; every pixel of a tile has the same).
std::vector<float> tile_samples(const fs::path& exr, int width, int height) {
  const std::vector<float> samples = cohort::read_exr_channel(exr, "samples");
  std::vector<float> tiles;
  for (int ty = 0; ty < height; ty += kTile)
    for (int tx = 0; tx < width; tx += kTile) {
      const float n = samples[std::size_t(ty) * width + tx];
      for (int y = ty; y < std::min(ty + kTile, height); ++y)
        for (int x = tx; x < std::min(tx + kTile, width); ++x)
          EXPECT_EQ(samples[std::size_t(y) * width + x], n) << "a tile's pixels stop together";
      tiles.push_back(n);
    }
  return tiles;
}

std::string tile_map(const std::vector<float>& tiles, int columns) {
  std::string map;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    char cell[16];
    std::snprintf(cell, sizeof(cell), "%4d", int(tiles[i]));
    map += cell;
    if ((i + 1) % columns == 0) map += "\n";
  }
  return map;
}

}  // namespace

TEST(Adaptive, EmptyBackgroundStopsAfterTheFirstRoundAndTheBoxTakesTheRest) {
  TempDir dir("cohort-adaptive-");
  const fs::path out = dir.path / "wide";
  const CommandResult r = run(wide_box(out, "--stats " + (dir.path / "wide.json").string()));
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path exr = out.string() + ".exr";
  const std::vector<float> tiles = tile_samples(exr, 64, 64);
  const cohort::Image image = cohort::read_exr(exr);
  constexpr int columns = 64 / kTile;
  std::printf("samples per %dx%d tile:\n%s", kTile, kTile, tile_map(tiles, columns).c_str());
  std::size_t background = 0;
  double box_samples = 0, box_tiles = 0;
  for (int t = 0; t < columns * columns; ++t) {
    bool empty = true;
    for (int y = t / columns * kTile; y < (t / columns + 1) * kTile; ++y)
      for (int x = t % columns * kTile; x < (t % columns + 1) * kTile; ++x)
        for (int c = 0; c < 3; ++c) empty = empty && image.pixel(x, y)[c] == 0.f;
    if (empty) {
      ++background;
      EXPECT_EQ(tiles[t], 16.f) << "tile " << t << " is empty background: it stops after the first round";
    } else {
      box_samples += tiles[t];
      ++box_tiles;
    }
  }
  ASSERT_GE(background, 8u) << "the wide view leaves empty tiles around the box";
  ASSERT_GE(box_tiles, 16) << "and the box covers tiles";
  EXPECT_GE(box_samples / box_tiles, 48) << "the box's tiles take the samples the background did not";
  EXPECT_EQ(*std::max_element(tiles.begin(), tiles.end()), 128.f) << "the noisiest tiles reach --spp";

  const auto stats = nlohmann::json::parse(read_all(dir.path / "wide.json"));
  const auto& adaptive = stats["adaptive"];
  const double spent = std::accumulate(tiles.begin(), tiles.end(), 0.0) * kTile * kTile;
  EXPECT_EQ(adaptive["samples"].get<double>(), spent);
  EXPECT_LT(spent, 0.75 * 128 * 64 * 64) << "a quarter of the uniform budget saved at least";
  EXPECT_EQ(adaptive["tiles"].get<int>(), columns * columns);
  EXPECT_GE(adaptive["tiles_stopped_early"].get<std::size_t>(), background);
  EXPECT_EQ(adaptive["max_pixel_spp"].get<int>(), 128);
  EXPECT_EQ(stats["image"]["spp"].get<int>(), 128) << "the image's spp is the most any pixel took";
  EXPECT_GT(stats["timings"]["render_cpu_seconds"].get<double>(), 0.0) << "the render loop's CPU time (the charts' clock)";
}

TEST(Adaptive, SameBitsTwiceForEveryMethodAndOnTwoDevices) {
  TempDir dir("cohort-adaptive-");
  const std::string line = "render " + shipped_scene("cornell-box.gltf") +
                           " --res 40x24 --fov 58 --spp 64 --pass-spp 4 --seed 5 --target-error 0.05 ";
  ASSERT_EQ(run(line + "-o " + (dir.path / "a").string()).code, 0);
  ASSERT_EQ(run(line + "-o " + (dir.path / "b").string()).code, 0);
  const std::string a = read_all(dir.path / "a.exr");
  EXPECT_EQ(a, read_all(dir.path / "b.exr")) << "two runs";
  const CommandResult pth = run(line + "--method pth -o " + (dir.path / "pth").string());
  ASSERT_EQ(pth.code, 0) << pth.output;
  EXPECT_EQ(a, read_all(dir.path / "pth.exr")) << "the default method and pth";
  // auto's probe splits launches by samples (not by rows: adaptive passes list their pixels)
  for (const char* method : {"naive", "auto"}) {
    const CommandResult other = run(line + "--method " + method + " -o " + (dir.path / method).string());
    ASSERT_EQ(other.code, 0) << other.output;
    EXPECT_EQ(a, read_all(dir.path / (std::string(method) + ".exr"))) << method;
  }
  EXPECT_NE(pth.output.find("estimated relative error"), std::string::npos) << pth.output;

  const std::string two = "env 'POCL_DEVICES=pthread pthread' ";
  if (run("devices", two).output.find("[1]") == std::string::npos) {
    std::printf("POCL_DEVICES=\"pthread pthread\" does not give two devices here: one device only\n");
    return;
  }
  const CommandResult r = run(line + "--device all --method sc+rg -o " + (dir.path / "two").string(), two);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("2 devices"), std::string::npos) << r.output;
  EXPECT_EQ(a, read_all(dir.path / "two.exr")) << "one device and two";
}

TEST(Adaptive, StoppedAndResumedEqualsAStraightRender) {
  TempDir dir("cohort-adaptive-");
  const std::string line = "render " + shipped_scene("cornell-box.gltf") +
                           " --res 64x64 --fov 58 --spp 128 --pass-spp 2 --seed 7 --target-error 0.05 ";
  ASSERT_EQ(run(line + "-o " + (dir.path / "full").string()).code, 0);
  // --time ends the first run after some pass, mid-round most likely; it saves its checkpoint
  const fs::path part = dir.path / "part";
  const CommandResult first = run(line + "--time 0.03 --checkpoint 100 -o " + part.string());
  ASSERT_EQ(first.code, 0) << first.output;
  if (read_all(part.string() + ".exr") == read_all(dir.path / "full.exr"))
    GTEST_SKIP() << "the render finished within --time";
  const CommandResult resumed = run(line + "--resume -o " + part.string());
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  EXPECT_EQ(read_all(part.string() + ".exr"), read_all(dir.path / "full.exr"));
}

// Relative MSE as the charts and the denoise test measure it: per pixel and channel
// (x - ref)^2 / (ref^2 + 0.01), averaged.
double relative_mse(const cohort::Image& x, const cohort::Image& ref) {
  double sum = 0;
  for (std::size_t i = 0; i < ref.rgb.size(); ++i) {
    const double d = x.rgb[i] - ref.rgb[i];
    sum += d * d / (double(ref.rgb[i]) * ref.rgb[i] + 0.01);
  }
  return sum / double(ref.rgb.size());
}

// Adaptive (--target-error E, at most --spp 256) against uniform sampling with the same total
// samples (the adaptive render's mean, rounded), both seed `seed`, each against a reference of
// `reference_spp` with seed 1 (independent noise). Returns {adaptive, uniform} relative MSE.
std::pair<double, double> adaptive_and_uniform(const std::string& view, double target_error, int seed,
                                               int reference_spp, int pixels) {
  TempDir dir("cohort-adaptive-");
  const CommandResult reference =
      run(view + "--spp " + std::to_string(reference_spp) + " --seed 1 -o " + (dir.path / "reference").string());
  EXPECT_EQ(reference.code, 0) << reference.output;
  const std::string seed_option = " --seed " + std::to_string(seed);
  const CommandResult adaptive = run(view + "--spp 256 --target-error " + std::to_string(target_error) + seed_option +
                                     " --stats " + (dir.path / "adaptive.json").string() + " -o " +
                                     (dir.path / "adaptive").string());
  EXPECT_EQ(adaptive.code, 0) << adaptive.output;
  const double spent = nlohmann::json::parse(read_all(dir.path / "adaptive.json"))["adaptive"]["samples"];
  const int uniform_spp = int(std::lround(spent / pixels));
  const CommandResult uniform =
      run(view + "--spp " + std::to_string(uniform_spp) + seed_option + " -o " + (dir.path / "uniform").string());
  EXPECT_EQ(uniform.code, 0) << uniform.output;
  const cohort::Image want = cohort::read_exr(dir.path / "reference.exr");
  const double e_adaptive = relative_mse(cohort::read_exr(dir.path / "adaptive.exr"), want);
  const double e_uniform = relative_mse(cohort::read_exr(dir.path / "uniform.exr"), want);
  std::printf("%.0f samples (%d spp uniform): relative MSE adaptive %.5f, uniform %.5f (%.3fx)\n", spent, uniform_spp,
              e_adaptive, e_uniform, e_adaptive / e_uniform);
  return {e_adaptive, e_uniform};
}

// Neither view has sky or empty background: every tile is noisy, some more than others, so
// adaptive sampling wins only by where it puts the samples. Stopping every tile at error E (the
// allocation before samples went in proportion to each tile's standard deviation) fails both:
// 1.03x uniform's relative MSE on the Sponza view, 1.07x on the box; the allocation now gives
// 0.94x and 0.79x. Other seeds (against longer references): 0.99-1.08x before, 0.86-0.93x now
// on the Sponza view (seeds 2-4); 0.64-1.07x before, 0.61-0.92x now on the box (seeds 2-5).
TEST(Adaptive, BeatsUniformAtAnEqualSampleBudgetOnTheSponzaInterior) {
  const fs::path sponza = fs::path(COHORT_SHARED_SCENES) / "crytek-sponza" / "sponza.obj.gz";
  if (!fs::exists(sponza)) GTEST_SKIP() << sponza << " is absent (an external model: scenes/external.json)";
  // the benchmark protocol's interior view: galleries, columns and floor, no sky in the frame
  const auto [adaptive, uniform] = adaptive_and_uniform(
      "render " + sponza.string() + " --white-sky --camera-bounds 0.25,0.2,0.5,0.75,0.35,0.5 --fov 60 --res 32x24 ",
      0.1, 3, 512, 32 * 24);
  EXPECT_LT(adaptive, uniform);
}

TEST(Adaptive, BeatsUniformAtAnEqualSampleBudgetOnTheCornellBox) {
  // the box fills the frame; the light's edge pixels (partly the light, 18x brighter than the
  // ceiling) are the noisiest, the shadowed corners next
  const auto [adaptive, uniform] =
      adaptive_and_uniform("render " + shipped_scene("cornell-box.gltf") + " --res 48x48 ", 0.08, 4, 512, 48 * 48);
  EXPECT_LT(adaptive, uniform);
}

TEST(Adaptive, BadTargetErrorIsExitTwoNamingTheOption) {
  TempDir dir("cohort-adaptive-");
  const std::string line = "render " + shipped_scene("cornell-box.gltf") + " --res 8x8 -o " + (dir.path / "x").string();
  for (const char* bad : {"0", "-0.1", "nan", "inf", "0.1x", "''"}) {
    const CommandResult r = run(line + " --spp 32 --target-error " + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--target-error"), std::string::npos) << bad << ": " << r.output;
  }
  const CommandResult within_first_round = run(line + " --spp 16 --target-error 0.1");
  EXPECT_EQ(within_first_round.code, 2) << within_first_round.output;
  EXPECT_NE(within_first_round.output.find("--spp"), std::string::npos) << within_first_round.output;
  EXPECT_FALSE(fs::exists(dir.path / "x.exr")) << "nothing is written";
}
