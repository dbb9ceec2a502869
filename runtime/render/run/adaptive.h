// Adaptive sampling (`--target-error E`). The render goes in rounds that end at fixed sample
// counts (16, 24, 32, 48, 64, 96, ...: each adds a half or a third, up to --spp). Every pixel
// takes the first round; at the end of each round, with every pass of the round in the film, each
// 4x4 tile estimates its relative error e_t from its pixels' running variance, hence its relative
// standard deviation per sample s_t = e_t sqrt(n_t). E is the image's target relative RMS error:
// the samples that reach it with the fewest in all are n_t proportional to s_t (minimise
// sum s_t^2 / n_t for a given sum n_t), so a tile goes on while n_t < s_t * s_mean / E^2
// (s_mean: the image's mean s_t). It then ends with error E sqrt(s_t / s_mean): noisy tiles
// keep more error than clean ones, and the image's mean relative squared error is E^2. Stopping
// every tile at the same error E instead spends n_t ~ s_t^2, which at an equal sample budget is
// no better than uniform sampling on the mean error.
//
// The decision reads the film at a round boundary, which is the same bits whatever devices, ranks
// or method made it (pass_schedule.h), so the pixels each round renders, and the image, depend on
// the seed and the settings only, never on timing. A sample's random numbers depend on its pixel
// and sample index alone (docs/decisions.md), so a pixel's samples are its first n whatever happens to
// its neighbours.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "runtime/render/run/checkpoint.h"

namespace cohort {

// Tiles of kAdaptiveTile^2 pixels stop together. 4x4 rather than 8x8: finer tiles follow the
// noise closer (Sponza interior at equal samples: 0.91x uniform's relative MSE against 0.93x),
// while 16 pixels x 16 samples still estimate s_t well (2x2 tiles needed a floor on s_t).
inline constexpr std::uint32_t kAdaptiveTile = 4;
inline constexpr std::uint32_t kAdaptiveFirstRound = 16;  // samples every pixel takes
// The relative squared error of a pixel is its variance over (mean^2 + this), as the relative MSE
// of the charts (scripts/lib/adaptive.py) and the denoise test: dark pixels do not demand endless samples.
inline constexpr double kRelativeErrorFloor = 0.01;

// The sample count at which the round holding sample `sample` ends, capped at spp (0: no cap).
std::uint32_t round_end(std::uint32_t sample, std::uint32_t spp);
// The first sample of the round holding `sample` (0, 16, 24, 32, 48, ...).
std::uint32_t round_start(std::uint32_t sample);

// The pixels one round renders, ascending; shared by every pass of the round.
using PixelList = std::shared_ptr<const std::vector<std::uint32_t>>;

struct TileGrid {
  std::uint32_t width = 0, height = 0;
  std::uint32_t columns() const { return (width + kAdaptiveTile - 1) / kAdaptiveTile; }
  std::uint32_t rows() const { return (height + kAdaptiveTile - 1) / kAdaptiveTile; }
  std::uint32_t count() const { return columns() * rows(); }
  std::uint32_t tile_of(std::uint32_t pixel) const {
    return (pixel / width) / kAdaptiveTile * columns() + (pixel % width) / kAdaptiveTile;
  }
  std::uint32_t tile_pixels(std::uint32_t tile) const {  // fewer at the right and bottom edges
    const std::uint32_t x = tile % columns() * kAdaptiveTile, y = tile / columns() * kAdaptiveTile;
    return (std::min(width, x + kAdaptiveTile) - x) * (std::min(height, y + kAdaptiveTile) - y);
  }
};

struct TileNoise {
  double error = 0;           // estimated relative RMS error of the tile's pixels (infinite below 2 samples)
  std::uint32_t samples = 0;  // the tile's sample count (its pixels stop together)
};

// Each tile's estimate: per pixel the variance of its mean luminance, from the film's sums of
// luminance (x, y, z) and of its square (w), over mean luminance^2 + kRelativeErrorFloor; the
// tile's error is the RMS over its pixels (the mean, as the image's mean error counts them).
std::vector<TileNoise> tile_noise(const FilmState& film);

// The samples each tile's share of the target error asks for: s_t * s_mean / E^2, with
// s_t = error * sqrt(samples) and s_mean its mean over the image's pixels; infinite where the
// estimate is not finite (a tile goes on).
std::vector<double> tile_sample_targets(const std::vector<TileNoise>& tiles, const TileGrid& grid,
                                        double target_error);

// What the round that starts at sample `start` renders, given the film at that point: every
// pixel at 0; else the pixels of the tiles that rendered the previous round (their pixels have
// `start` samples) and have fewer than their tile_sample_targets. Empty: every tile is done.
std::vector<std::uint32_t> round_pixels(const FilmState& film, std::uint32_t start, double target_error);

// The pixels of a round resumed in its middle, at sample `at`: those with `at` samples (a
// checkpoint stops at a pass boundary, and the round's pixels all have the same count there).
std::vector<std::uint32_t> pixels_with_samples(const FilmState& film, std::uint32_t at);

// Figures of an adaptive film for --stats and -v.
struct AdaptiveFigures {
  std::uint64_t samples = 0;        // spent, over all pixels
  std::uint32_t tiles = 0;
  std::uint32_t tiles_stopped = 0;  // tiles that stopped early (fewer samples than the film's last pass)
  std::uint32_t tiles_converged = 0;  // tiles at their tile_sample_targets in the final film
  double estimated_error = 0;  // the final film's estimated relative RMS error (pixel mean): about E
  std::uint32_t min_pixel_samples = 0, max_pixel_samples = 0;
};
AdaptiveFigures adaptive_figures(const FilmState& film, double target_error);

}  // namespace cohort
