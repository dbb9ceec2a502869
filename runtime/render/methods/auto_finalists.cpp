#include "runtime/render/methods/auto_finalists.h"

#include <algorithm>
#include <cmath>

namespace cohort {

std::vector<std::size_t> auto_finalists(std::span<const ScreenedMethod> screened, double keep, std::size_t finalists) {
  double best = -1;
  for (const ScreenedMethod& m : screened) best = std::max(best, m.rate);
  std::vector<std::size_t> kept;
  if (best < 0 || finalists == 0) return kept;
  for (std::size_t i = 0; i < screened.size(); ++i)
    if (screened[i].rate >= 0 && screened[i].rate >= keep * best) kept.push_back(i);
  std::stable_sort(kept.begin(), kept.end(),
                   [&](std::size_t x, std::size_t y) { return screened[x].rate > screened[y].rate; });
  if (kept.size() > finalists) {
    const auto sorting = std::find_if(kept.begin(), kept.end(), [&](std::size_t i) { return screened[i].sorts; });
    const auto last = kept.begin() + static_cast<std::ptrdiff_t>(finalists - 1);
    // with a single place there is no final to run: the screen's best keeps it
    if (finalists >= 2 && sorting != kept.end() && sorting > last) std::rotate(last, sorting, sorting + 1);
    kept.resize(finalists);
  }
  return kept;
}

std::size_t auto_pick(std::span<const double> rates, std::size_t default_index, double default_second_rate,
                      double min_margin) {
  const double first = rates[default_index];
  const double reference = std::max(first, default_second_rate);
  const double noise = reference > 0 && first >= 0 && default_second_rate >= 0
                           ? std::abs(first - default_second_rate) / reference
                           : 0.0;
  const double bar = reference * (1.0 + std::max(min_margin, 2.0 * noise));
  std::size_t pick = default_index;
  for (std::size_t i = 0; i < rates.size(); ++i)
    if (i != default_index && rates[i] > bar && (pick == default_index || rates[i] > rates[pick])) pick = i;
  return pick;
}

}  // namespace cohort
