// Adaptive sampling (`--target-error E`). The render goes in rounds that end at fixed sample
// counts (16, 24, 32, 48, 64, 96, ...: each adds a half or a third, up to --spp). Every pixel
// takes the first round; at the end of each round, with every pass of the round in the film, each
// 8x8 tile still rendering estimates its relative error from its pixels' running variance, and a
// tile below E stops there. The next round renders the other tiles' pixels only.
//
// The decision reads the film at a round boundary, which is the same bits whatever devices, ranks
// or method made it (pass_schedule.h), so the pixels each round renders, and the image, depend on
// the seed and the settings only, never on timing. A sample's random numbers depend on its pixel
// and sample index alone (DECISIONS.md), so a pixel's samples are its first n whatever happens to
// its neighbours.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "runtime/render/checkpoint.h"

namespace cohort {

inline constexpr std::uint32_t kAdaptiveTile = 8;   // tiles of kAdaptiveTile^2 pixels stop together
inline constexpr std::uint32_t kAdaptiveBlock = 4;  // a tile's error is its worst block's of this size
static_assert(kAdaptiveTile % kAdaptiveBlock == 0, "a tile is whole blocks");
inline constexpr std::uint32_t kAdaptiveFirstRound = 16;  // samples every pixel takes
// The relative squared error of a pixel is its variance over (mean^2 + this), as the relative MSE
// of the charts (scripts/adaptive.py) and the denoise test: dark pixels do not demand endless samples.
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
};

// Estimated relative RMS error of each tile of `film`: per pixel the variance of its mean, from
// the film's sums of luminance (x, y, z) and of its square (w), over mean luminance^2 +
// kRelativeErrorFloor; averaged over each 4x4 block and square-rooted; a tile's error is its worst
// block's (a tile half empty background, half noise is not averaged down). A block with a pixel of
// fewer than 2 samples has infinite error.
std::vector<double> tile_errors(const FilmState& film);

// What the round that starts at sample `start` renders, given the film at that point: every
// pixel at 0; else the pixels of the tiles that rendered the previous round (their pixels have
// `start` samples) whose estimated error is at least `target_error`. Empty: every tile is done.
std::vector<std::uint32_t> round_pixels(const FilmState& film, std::uint32_t start, double target_error);

// The pixels of a round resumed in its middle, at sample `at`: those with `at` samples (a
// checkpoint stops at a pass boundary, and the round's pixels all have the same count there).
std::vector<std::uint32_t> pixels_with_samples(const FilmState& film, std::uint32_t at);

// The samples every pixel of `film` has.
std::uint32_t fewest_samples(const FilmState& film);

// Figures of an adaptive film for --stats and -v.
struct AdaptiveFigures {
  std::uint64_t samples = 0;        // spent, over all pixels
  std::uint32_t tiles = 0;
  std::uint32_t tiles_stopped = 0;  // tiles that stopped early (fewer samples than the film's last pass)
  std::uint32_t tiles_converged = 0;  // tiles whose estimated error in the final film is below the target
  std::uint32_t min_pixel_samples = 0, max_pixel_samples = 0;
};
AdaptiveFigures adaptive_figures(const FilmState& film, double target_error);

}  // namespace cohort
