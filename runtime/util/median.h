// The median of a set of measurements (the mean of the middle two for an even count; 0 when empty).
#pragma once

#include <algorithm>
#include <vector>

namespace cohort {

inline double median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace cohort
