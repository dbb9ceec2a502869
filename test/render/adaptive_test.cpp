// Adaptive sampling's pieces (runtime/render/adaptive.h): rounds end at fixed sample counts and
// every round is whole passes; a tile's error estimate; which pixels a round renders; and a job
// that stops tiles, counts each pixel's samples and ends once every tile is done.
#include <gtest/gtest.h>

#include <cmath>

#include "runtime/render/adaptive.h"
#include "runtime/render/pass_job.h"

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
  for (const double e : tile_errors(film_of(16, 8, 16, grey, 0.f))) EXPECT_EQ(e, 0.0);
  // sum of squares raised by 15 * 0.01: sample variance 0.01 over 16 samples, so the mean's
  // variance is 0.01 / 16 and the relative error sqrt(0.01 / 16 / (0.25 + 0.01))
  const std::vector<double> errors = tile_errors(film_of(16, 8, 16, grey, 15 * 0.01f));
  ASSERT_EQ(errors.size(), 2u);
  for (const double e : errors) EXPECT_NEAR(e, std::sqrt(0.01 / 16 / 0.26), 1e-4);
}

TEST(AdaptiveError, ATileIsAsBadAsItsWorstBlock) {
  // one noisy 4x4 block in the second tile of an 16x8 image: the tile's error is that block's
  FilmState f = film_of(16, 8, 16, [](std::uint32_t) { return 0.5f; }, 0.f);
  for (std::uint32_t y = 4; y < 8; ++y)
    for (std::uint32_t x = 12; x < 16; ++x) f.sums[y * 16 + x].w += 15 * 0.01f;
  const std::vector<double> errors = tile_errors(f);
  EXPECT_EQ(errors[0], 0.0);
  EXPECT_NEAR(errors[1], std::sqrt(0.01 / 16 / 0.26), 1e-4);
  // the next round renders the noisy tile's pixels only, ascending
  const std::vector<std::uint32_t> next = round_pixels(f, 16, 0.001);
  ASSERT_EQ(next.size(), 64u);
  EXPECT_EQ(next.front(), 8u);
  EXPECT_EQ(next.back(), 127u);
  EXPECT_TRUE(round_pixels(f, 16, 0.1).empty()) << "both tiles below a looser target";
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
    // tile 0 is constant (below any target at once); tile 1's samples vary (variance ~0.5, a
    // relative error of 0.17 at 64 spp): it goes on to --spp
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
  EXPECT_EQ(figures.tiles, 2u);
  EXPECT_EQ(figures.tiles_stopped, 1u);
  // film_image divides each pixel by its own count
  const Image image = film_image(film);
  EXPECT_EQ(image.rgb[0], 0.5f);
  EXPECT_EQ(image.rgb[3 * 8], 0.5f);
}
