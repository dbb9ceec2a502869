#include "runtime/render/scene/discrete_cdf.h"

namespace cohort {

std::vector<float> discrete_cdf(const std::vector<double>& weights) {
  std::vector<float> cdf;
  if (weights.empty()) return cdf;
  double total = 0;
  for (double w : weights) total += w;
  const bool uniform = !(total > 0);
  if (uniform) total = static_cast<double>(weights.size());
  double running = 0;
  cdf.reserve(weights.size());
  for (double w : weights) {
    running += uniform ? 1.0 : w;
    cdf.push_back(static_cast<float>(running / total));
  }
  cdf.back() = 1.f;
  return cdf;
}

}  // namespace cohort
