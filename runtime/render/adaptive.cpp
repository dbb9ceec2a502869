#include "runtime/render/adaptive.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cohort {
namespace {

// The round boundaries past the first: 2^k and 1.5 * 2^k, as 64-bit values (no wrap near 2^32).
std::uint64_t boundary_after(std::uint64_t sample) {
  if (sample < kAdaptiveFirstRound) return kAdaptiveFirstRound;
  std::uint64_t power = kAdaptiveFirstRound;
  while (power * 2 <= sample) power *= 2;
  return sample < power + power / 2 ? power + power / 2 : power * 2;
}

}  // namespace

std::uint32_t round_end(std::uint32_t sample, std::uint32_t spp) {
  const std::uint64_t end = std::min<std::uint64_t>(boundary_after(sample), UINT32_MAX);
  return static_cast<std::uint32_t>(spp ? std::min<std::uint64_t>(end, spp) : end);
}

std::uint32_t round_start(std::uint32_t sample) {
  if (sample < kAdaptiveFirstRound) return 0;
  std::uint64_t start = kAdaptiveFirstRound;
  for (std::uint64_t next = boundary_after(start); next <= sample; next = boundary_after(next)) start = next;
  return static_cast<std::uint32_t>(start);
}

std::vector<double> tile_errors(const FilmState& film) {
  // per block of kAdaptiveBlock^2 pixels: the sum of its pixels' relative squared errors
  const std::uint32_t block_columns = (film.width + kAdaptiveBlock - 1) / kAdaptiveBlock;
  const std::uint32_t block_rows = (film.height + kAdaptiveBlock - 1) / kAdaptiveBlock;
  std::vector<double> sum(std::size_t(block_columns) * block_rows, 0.0);
  std::vector<std::uint32_t> pixels(sum.size(), 0);
  for (std::uint32_t i = 0; i < film.sums.size(); ++i) {
    const std::uint32_t column = i % film.width, row = i / film.width;
    const std::size_t block = std::size_t(row / kAdaptiveBlock) * block_columns + column / kAdaptiveBlock;
    const double n = film.pixel_samples.empty() ? film.samples : film.pixel_samples[i];
    ++pixels[block];
    if (n < 2) {
      sum[block] = std::numeric_limits<double>::infinity();
      continue;
    }
    const co_float4 s = film.sums[i];
    // the luminance weights of film_add_sample (pathtrace.h); sums are linear, so this is the sum
    // of the samples' luminances
    const double y = 0.2126 * s.x + 0.7152 * s.y + 0.0722 * s.z;
    const double mean = y / n;
    const double variance = std::max(0.0, (double(s.w) - y * mean) / (n - 1));  // of one sample
    sum[block] += variance / n / (mean * mean + kRelativeErrorFloor);
  }
  // a tile's error: its worst block's RMS (a tile half background, half noise is not averaged down)
  const TileGrid grid{film.width, film.height};
  std::vector<double> errors(grid.count(), 0.0);
  for (std::uint32_t by = 0; by < block_rows; ++by)
    for (std::uint32_t bx = 0; bx < block_columns; ++bx) {
      const std::size_t block = std::size_t(by) * block_columns + bx;
      const std::uint32_t tile = (by * kAdaptiveBlock / kAdaptiveTile) * grid.columns() + bx * kAdaptiveBlock / kAdaptiveTile;
      errors[tile] = std::max(errors[tile], std::sqrt(sum[block] / std::max<std::uint32_t>(pixels[block], 1)));
    }
  return errors;
}

std::vector<std::uint32_t> pixels_with_samples(const FilmState& film, std::uint32_t at) {
  std::vector<std::uint32_t> list;
  for (std::uint32_t i = 0; i < film.sums.size(); ++i)
    if (film.pixel_samples.empty() ? film.samples == at : film.pixel_samples[i] == at) list.push_back(i);
  return list;
}

std::vector<std::uint32_t> round_pixels(const FilmState& film, std::uint32_t start, double target_error) {
  std::vector<std::uint32_t> list;
  if (start == 0) {
    list.resize(film.sums.size());
    for (std::uint32_t i = 0; i < list.size(); ++i) list[i] = i;
    return list;
  }
  const TileGrid grid{film.width, film.height};
  const std::vector<double> errors = tile_errors(film);
  for (std::uint32_t i = 0; i < film.sums.size(); ++i) {
    const bool rendered_last_round = film.pixel_samples.empty() || film.pixel_samples[i] == start;
    // `!(e < E)`: a tile whose estimate is NaN goes on
    if (rendered_last_round && !(errors[grid.tile_of(i)] < target_error)) list.push_back(i);
  }
  return list;
}

std::uint32_t fewest_samples(const FilmState& film) {
  if (film.pixel_samples.empty()) return film.samples;
  return *std::min_element(film.pixel_samples.begin(), film.pixel_samples.end());
}

AdaptiveFigures adaptive_figures(const FilmState& film, double target_error) {
  AdaptiveFigures f;
  const TileGrid grid{film.width, film.height};
  f.tiles = grid.count();
  if (film.pixel_samples.empty()) {
    f.samples = std::uint64_t(film.samples) * film.sums.size();
    f.min_pixel_samples = f.max_pixel_samples = film.samples;
  } else {
    f.min_pixel_samples = UINT32_MAX;
    std::vector<bool> stopped(grid.count(), false);
    for (std::uint32_t i = 0; i < film.pixel_samples.size(); ++i) {
      const std::uint32_t n = film.pixel_samples[i];
      f.samples += n;
      f.min_pixel_samples = std::min(f.min_pixel_samples, n);
      f.max_pixel_samples = std::max(f.max_pixel_samples, n);
      if (n < film.samples) stopped[grid.tile_of(i)] = true;
    }
    f.tiles_stopped = static_cast<std::uint32_t>(std::count(stopped.begin(), stopped.end(), true));
  }
  if (target_error > 0)
    for (const double e : tile_errors(film)) f.tiles_converged += e < target_error ? 1 : 0;
  return f;
}

}  // namespace cohort
