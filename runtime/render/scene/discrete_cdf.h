// The discrete distributions the kernels pick lights and environment cells from.
#pragma once

#include <cstddef>
#include <vector>

namespace cohort {

// Inclusive running sums of `weights` over their total, with the last entry exactly 1 (no
// rounding gap at the top); all-zero weights give the uniform cdf. Empty in, empty out.
std::vector<float> discrete_cdf(const std::vector<double>& weights);

// Probability of step i as the kernels' binary search realises it: the difference of neighbours.
inline float cdf_step(const std::vector<float>& cdf, std::size_t i) { return cdf[i] - (i == 0 ? 0.f : cdf[i - 1]); }

}  // namespace cohort
