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

// The final round's pick. The device's default method (device_default_method) is timed twice, first
// and last; the spread of its two rates is the probe's own noise. Another method replaces it only
// when its rate beats the default's better one by more than that noise, twice over, and at least
// by `min_margin`: on a shared machine the rates move more than the methods differ, and a pick made
// on noise can be several times slower than the default (a CPU, where the megakernel is rarely
// beaten). `rates` are the final's rays per second (negative: not timed); returns an index into them.
std::size_t auto_pick(std::span<const double> rates, std::size_t default_index, double default_second_rate,
                      double min_margin);

}  // namespace cohort
