// Which methods auto's final round times, from the screen's rates: a pure function, so that the
// rule is tested without a device.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace cohort {

struct ScreenedMethod {
  double rate = -1;    // rays per second in the screen; negative: not screened
  bool sorts = false;  // sorts the rays of later bounces (hash, pth)
};

// Indices of the methods within `keep` of the screen's best rate, fastest first (ties in table
// order), at most `finalists`. A quarter wave understates the sorting methods, whose ordering pays
// with full waves (the gate benchmark): when none of them made the cut but one passed `keep`, the
// fastest such takes the last place (with at least two places: one place is the screen's pick).
// Empty when nothing was screened.
std::vector<std::size_t> auto_finalists(std::span<const ScreenedMethod> screened, double keep, std::size_t finalists);

}  // namespace cohort
