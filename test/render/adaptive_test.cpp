// Adaptive sampling's pieces (runtime/render/run/adaptive.h): rounds end at fixed sample counts and
// every round is whole passes; a tile's error estimate; which pixels a round renders; and a job
// that stops tiles, counts each pixel's samples and ends once every tile is done.
#include <gtest/gtest.h>

#include <cmath>

#include "runtime/render/run/adaptive.h"
#include "runtime/render/run/pass_job.h"

using namespace cohort;

namespace {

// A film of w x h pixels with n samples each, every sample of pixel i equal to value(i) (luminance
// for a grey pixel), plus `noise` of extra sum of squares: variance without changing the mean.
FilmState film_of(std::uint32_t w, std::uint32_t h, std::uint32_t n, float (*value)(std::uint32_t), float noise) {
  FilmState f;
  f.width = w;
  f.height = h;
  f.samples = n;
  f.pass_samples = n;
  f.pixel_samples.assign(std::size_t(w) * h, n);
  for (std::uint32_t i = 0; i < w * h; ++i) {
    const float v = value(i);
    f.sums.push_back(co_float4{v * float(n), v * float(n), v * float(n), v * v * float(n) + noise});
  }
  return f;
}

}  // namespace

TEST(AdaptiveRounds, EndAtSixteenThenAddAHalfOrAThird) {
  std::vector<std::uint32_t> ends;
  for (std::uint32_t s = 0; s < 200; s = round_end(s, 0)) ends.push_back(round_end(s, 0));
  EXPECT_EQ(ends, (std::vector<std::uint32_t>{16, 24, 32, 48, 64, 96, 128, 192, 256}));
  EXPECT_EQ(round_end(100, 100 + 1), 101u) << "--spp caps the last round";
  EXPECT_EQ(round_start(0), 0u);
  EXPECT_EQ(round_start(15), 0u);
  EXPECT_EQ(round_start(16), 16u);
  EXPECT_EQ(round_start(47), 32u);
  EXPECT_EQ(round_start(48), 48u);
  EXPECT_EQ(round_end(UINT32_MAX - 1, 0), UINT32_MAX) << "no wrap near 2^32";
}

TEST(AdaptiveRounds, PassesEndAtEveryRoundEndAndAResumeContinuesTheSameSchedule) {
  const PassSchedule straight(10, 0, 100, true);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> passes;
  for (std::uint32_t i = 0; const auto p = straight.pass(i); ++i) {
    EXPECT_EQ(p->index, i);
    if (!passes.empty()) {
      EXPECT_EQ(p->first_sample, passes.back().first + passes.back().second) << "in order, no gap";
    }
    EXPECT_EQ(round_start(p->first_sample), round_start(p->first_sample + p->samples - 1)) << "inside one round";
    passes.emplace_back(p->first_sample, p->samples);
  }
  // rounds 16, 24, 32, 48, 64, 96, 100 cut passes of 10
  EXPECT_EQ(passes, (std::vector<std::pair<std::uint32_t, std::uint32_t>>{
                        {0, 10}, {10, 6}, {16, 8}, {24, 8}, {32, 10}, {42, 6}, {48, 10}, {58, 6}, {64, 10},
                        {74, 10}, {84, 10}, {94, 2}, {96, 4}}));
  // a checkpoint after the pass ending at 74 resumes with the same passes
  const PassSchedule resumed(10, 74, 100, true);
  for (std::uint32_t i = 0; const auto p = resumed.pass(i); ++i) {
    ASSERT_LT(9 + i, passes.size());
    EXPECT_EQ(p->first_sample, passes[9 + i].first);
    EXPECT_EQ(p->samples, passes[9 + i].second);
  }
}

TEST(AdaptiveError, ZeroForConstantPixelsAndTheRelativeStandardErrorOtherwise) {
  const auto grey = [](std::uint32_t) { return 0.5f; };
  for (const TileNoise& t : tile_noise(film_of(16, 8, 16, grey, 0.f))) {
    EXPECT_EQ(t.error, 0.0);
    EXPECT_EQ(t.samples, 16u);
  }
  // sum of squares raised by 15 * 0.01: sample variance 0.01 over 16 samples, so the mean's
  // variance is 0.01 / 16 and the relative error sqrt(0.01 / 16 / (0.25 + 0.01))
  const std::vector<TileNoise> tiles = tile_noise(film_of(16, 8, 16, grey, 15 * 0.01f));
  ASSERT_EQ(tiles.size(), 8u) << "4x4 tiles";
  for (const TileNoise& t : tiles) EXPECT_NEAR(t.error, std::sqrt(0.01 / 16 / 0.26), 1e-4);
}

TEST(AdaptiveError, ATileIsTheMeanOfItsPixelsAndEdgeTilesCountTheirOwnPixels) {
  // 6x4: tiles of 4x4 and 2x4 pixels; one noisy pixel in each
  FilmState f = film_of(6, 4, 16, [](std::uint32_t) { return 0.5f; }, 0.f);
  f.sums[0].w += 15 * 0.01f;
  f.sums[5].w += 15 * 0.01f;
  const std::vector<TileNoise> tiles = tile_noise(f);
  ASSERT_EQ(tiles.size(), 2u);
  EXPECT_NEAR(tiles[0].error, std::sqrt(0.01 / 16 / 0.26 / 16), 1e-5);
  EXPECT_NEAR(tiles[1].error, std::sqrt(0.01 / 16 / 0.26 / 8), 1e-5);
}

TEST(AdaptiveTargets, SamplesInProportionToEachTilesStandardDeviationSoTheMeanErrorIsE) {
  // 16x8, eight 4x4 tiles: tile 0 constant, tile 1 with variance v, tile 2 with 4v, the rest v
  FilmState f = film_of(16, 8, 16, [](std::uint32_t) { return 0.5f; }, 0.f);
  const float v = 0.01f;
  for (std::uint32_t i = 0; i < 128; ++i) {
    const std::uint32_t tile = TileGrid{16, 8}.tile_of(i);
    if (tile != 0) f.sums[i].w += 15 * v * (tile == 2 ? 4.f : 1.f);
  }
  const std::vector<TileNoise> tiles = tile_noise(f);
  const double s = std::sqrt(v / 0.26);  // relative standard deviation of one sample of a v tile
  const double mean_s = (0 + 2 * s + 6 * s) / 8;
  const double e = 0.05;
  const std::vector<double> targets = tile_sample_targets(tiles, TileGrid{16, 8}, e);
  EXPECT_EQ(targets[0], 0.0) << "a clean tile needs no more samples";
  EXPECT_NEAR(targets[1], s * mean_s / (e * e), 1e-3);
  EXPECT_NEAR(targets[2], 2 * targets[1], 1e-3) << "twice the standard deviation (4x the variance): twice the samples";
  // with every tile at its target, the mean relative squared error over the pixels is E^2
  double mean_square = 0;
  for (std::size_t t = 1; t < 8; ++t) mean_square += (t == 2 ? 4 : 1) * (s * s) / targets[t] / 8;
  EXPECT_NEAR(mean_square, e * e, 1e-6);  // the film is float
  // mean_s = s, so targets[1] = s^2 / E^2 = 15.4 and targets[2] = 30.8: at 16 samples the v
  // tiles stop and tile 2 goes on
  const std::vector<std::uint32_t> next = round_pixels(f, 16, e);
  ASSERT_EQ(next.size(), 16u) << "only the noisiest tile goes on";
  for (const std::uint32_t i : next) EXPECT_EQ((TileGrid{16, 8}.tile_of(i)), 2u);
  EXPECT_EQ(round_pixels(f, 16, 0.04).size(), 7u * 16) << "E 0.04: targets 24 and 48, every noisy tile goes on";
}

TEST(AdaptiveJob, StopsCleanTilesCountsEachPixelAndEndsWhenEveryTileIsDone) {
  RenderSettings s;
  s.width = 16;
  s.height = 8;
  s.spp = 64;
  s.pass_samples = 8;
  s.target_error = 0.05;
  PassJob job(s, {}, {}, 1, 0);
  std::vector<std::uint32_t> rendered;  // pixels of each pass handed out
  while (const auto pass = job.next()) {
    // the left half is constant (no more samples needed at once); the right half's samples vary
    // (variance ~0.5: relative standard deviation ~1.4 per sample, the image's mean ~0.7, so
    // 1.4 * 0.7 / 0.05^2 ~ 400 samples): it goes on to --spp
    PassFilm film{*pass, std::vector<co_float4>(128), 0, 0};
    const std::size_t count = pass->pixels ? pass->pixels->size() : 128;
    rendered.push_back(static_cast<std::uint32_t>(count));
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t pixel = pass->pixels ? (*pass->pixels)[k] : static_cast<std::uint32_t>(k);
      const float n = float(pass->samples);
      const float extra = pixel % 16 >= 8 ? 0.5f * n : 0.f;
      film.sums[pixel] = co_float4{0.5f * n, 0.5f * n, 0.5f * n, 0.25f * n + extra};
    }
    job.deliver(std::move(film));
  }
  const FilmState film = job.finish();
  // first round (16 spp) in two passes of every pixel, then tile 1's 64 pixels
  ASSERT_GE(rendered.size(), 3u);
  EXPECT_EQ(rendered[0], 128u);
  EXPECT_EQ(rendered[1], 128u);
  for (std::size_t i = 2; i < rendered.size(); ++i) EXPECT_EQ(rendered[i], 64u);
  for (std::uint32_t i = 0; i < 128; ++i) EXPECT_EQ(film.pixel_samples[i], i % 16 < 8 ? 16u : 64u) << i;
  EXPECT_EQ(film.samples, 64u);
  const AdaptiveFigures figures = adaptive_figures(film, s.target_error);
  EXPECT_EQ(figures.samples, 64u * 16 + 64u * 64);
  EXPECT_EQ(figures.tiles, 8u);
  EXPECT_EQ(figures.tiles_stopped, 4u);
  // film_image divides each pixel by its own count
  const Image image = film_image(film);
  EXPECT_EQ(image.rgb[0], 0.5f);
  EXPECT_EQ(image.rgb[3 * 8], 0.5f);
}
