#include "runtime/render/run/adaptive.h"

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

std::vector<TileNoise> tile_noise(const FilmState& film) {
  const TileGrid grid{film.width, film.height};
  std::vector<TileNoise> tiles(grid.count());
  std::vector<double> sum(grid.count(), 0.0);  // of the pixels' relative squared errors
  for (std::uint32_t i = 0; i < film.sums.size(); ++i) {
    const std::uint32_t tile = grid.tile_of(i);
    const std::uint32_t n = film.pixel_samples.empty() ? film.samples : film.pixel_samples[i];
    tiles[tile].samples = n;
    if (n < 2) {
      sum[tile] = std::numeric_limits<double>::infinity();
      continue;
    }
    const co_float4 s = film.sums[i];
    // the luminance weights of film_add_sample (pathtrace.h); sums are linear, so this is the sum
    // of the samples' luminances
    const double y = 0.2126 * s.x + 0.7152 * s.y + 0.0722 * s.z;
    const double mean = y / n;
    const double variance = std::max(0.0, (double(s.w) - y * mean) / (n - 1));  // of one sample
    sum[tile] += variance / n / (mean * mean + kRelativeErrorFloor);
  }
  for (std::uint32_t t = 0; t < tiles.size(); ++t) tiles[t].error = std::sqrt(sum[t] / grid.tile_pixels(t));
  return tiles;
}

std::vector<double> tile_sample_targets(const std::vector<TileNoise>& tiles, const TileGrid& grid,
                                        double target_error) {
  std::vector<double> spread(tiles.size());  // s_t: relative standard deviation of one sample
  double spread_sum = 0, pixels = 0;
  for (std::uint32_t t = 0; t < tiles.size(); ++t) {
    spread[t] = tiles[t].error * std::sqrt(double(tiles[t].samples));
    if (std::isfinite(spread[t])) spread_sum += spread[t] * grid.tile_pixels(t), pixels += grid.tile_pixels(t);
  }
  const double mean_spread = pixels > 0 ? spread_sum / pixels : 0;
  std::vector<double> targets(tiles.size());
  for (std::uint32_t t = 0; t < tiles.size(); ++t)
    targets[t] = std::isfinite(spread[t]) ? spread[t] * mean_spread / (target_error * target_error)
                                          : std::numeric_limits<double>::infinity();
  return targets;
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
  const std::vector<double> targets = tile_sample_targets(tile_noise(film), grid, target_error);
  for (std::uint32_t i = 0; i < film.sums.size(); ++i) {
    const bool rendered_last_round = film.pixel_samples.empty() || film.pixel_samples[i] == start;
    // `!(start >= target)`: a NaN target goes on
    if (rendered_last_round && !(double(start) >= targets[grid.tile_of(i)])) list.push_back(i);
  }
  return list;
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
  if (target_error > 0) {
    const std::vector<TileNoise> tiles = tile_noise(film);
    const std::vector<double> targets = tile_sample_targets(tiles, grid, target_error);
    double squares = 0;
    for (std::uint32_t t = 0; t < tiles.size(); ++t) {
      f.tiles_converged += tiles[t].samples >= targets[t] ? 1 : 0;
      squares += tiles[t].error * tiles[t].error * grid.tile_pixels(t);
    }
    f.estimated_error = std::sqrt(squares / std::max<double>(film.sums.size(), 1));
  }
  return f;
}

}  // namespace cohort
