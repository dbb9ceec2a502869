// Binned SAH plane search for large nodes (Wald 2007 for BVHs; Shevtsov et al. 2007 and Hunt et
// al. 2006 for KD-trees): every reference adds its start to the bin of its lower bound and its end
// to the bin of its upper bound; prefix sums over the bins then give, for each bin boundary, how
// many references reach left of it and how many right of it. The counts are integers, so a
// parallel count gives the same plane as a serial one.
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
namespace {

constexpr std::size_t kParallelGrain = 16384;  // references per task when counting in parallel

// Maps positions in the cell to bins; positions outside (none, but rounding) clamp to the ends.
// Monotone in the position: subtraction, scaling and truncation all preserve order.
struct Binner {
  glm::vec3 lo;
  glm::vec3 scale;  // bins / extent, 0 along a flat axis
  int bins;

  int bin(int axis, float x) const {
    const float f = (x - lo[axis]) * scale[axis];
    return std::clamp(static_cast<int>(f), 0, bins - 1);
  }
};

// Start and end counts, [axis * bins + bin].
struct BinCounts {
  std::vector<std::uint32_t> starts, ends;

  void reset(int bins) {
    starts.assign(3 * static_cast<std::size_t>(bins), 0u);
    ends.assign(3 * static_cast<std::size_t>(bins), 0u);
  }
  void add(const BinCounts& other) {
    for (std::size_t i = 0; i < starts.size(); ++i) {
      starts[i] += other.starts[i];
      ends[i] += other.ends[i];
    }
  }
};

void count(const Binner& binner, std::span<const Ref> refs, std::vector<std::uint32_t>& starts,
           std::vector<std::uint32_t>& ends) {
  for (const Ref& r : refs) {
    for (int axis = 0; axis < 3; ++axis) {
      ++starts[axis * binner.bins + binner.bin(axis, r.box.lo[axis])];
      ++ends[axis * binner.bins + binner.bin(axis, r.box.hi[axis])];
    }
  }
}

void count_all(const Binner& binner, std::span<const Ref> refs, bool parallel,
               PlaneScratch& scratch) {
  if (!parallel || refs.size() <= 2 * kParallelGrain) {
    scratch.starts.assign(3 * static_cast<std::size_t>(binner.bins), 0u);
    scratch.ends.assign(3 * static_cast<std::size_t>(binner.bins), 0u);
    count(binner, refs, scratch.starts, scratch.ends);
    return;
  }
  BinCounts empty;
  empty.reset(binner.bins);
  BinCounts total = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, refs.size(), kParallelGrain), empty,
      [&](const tbb::blocked_range<std::size_t>& r, BinCounts partial) {
        count(binner, refs.subspan(r.begin(), r.size()), partial.starts, partial.ends);
        return partial;
      },
      [](BinCounts a, const BinCounts& b) {
        a.add(b);
        return a;
      });
  scratch.starts = std::move(total.starts);
  scratch.ends = std::move(total.ends);
}

// The best bin boundary of one axis (0: none) with its plane.
int best_boundary(const SahContext& c, const Binner& binner, const PlaneScratch& counts, int axis,
                  SplitPlane& axis_best) {
  const int bins = binner.bins;
  const float step = c.extent[axis] / static_cast<float>(bins);
  const AxisSah a = axis_sah(c, axis);
  int boundary = 0;
  std::uint32_t n_left = 0, n_right = c.count;
  for (int b = 1; b < bins; ++b) {
    // Boundary b: references starting in a lower bin reach left of it, those ending in a lower
    // bin do not reach right of it.
    n_left += counts.starts[axis * bins + b - 1];
    n_right -= counts.ends[axis * bins + b - 1];
    const float pos = c.lo[axis] + step * static_cast<float>(b);
    if (!(pos > c.lo[axis] && pos < c.hi[axis])) continue;
    evaluate_plane(c, a, pos, n_left, n_right, 0, axis_best);
    if (axis_best.valid() && axis_best.pos == pos) boundary = b;
  }
  return boundary;
}

// Exact counts inside bins [b - 1, b] of an axis: every reference starting in a lower bin lies
// left of each event there, every one ending in a lower bin right of none (the bin index is
// monotone in the position), so a Wald & Havran sweep over the events in those bins, started from
// the prefix counts, evaluates each of them exactly. This recovers the planes that cut off empty
// space tightly, which bin boundaries miss and which a KD-tree's cost depends on.
void refine(const SahContext& c, const Binner& binner, std::span<const Ref> refs,
            const std::array<int, 3>& boundary, PlaneScratch& scratch, SplitPlane& best) {
  for (auto& list : scratch.events) list.clear();
  for (std::size_t i = 0; i < refs.size(); ++i) {
    const Bounds& box = refs[i].box;
    const auto local = static_cast<std::uint32_t>(i);
    for (int axis = 0; axis < 3; ++axis) {
      if (boundary[axis] == 0) continue;
      const int first = boundary[axis] - 1, last = boundary[axis];
      const int lo = binner.bin(axis, box.lo[axis]), hi = binner.bin(axis, box.hi[axis]);
      std::vector<Event>& list = scratch.events[axis];
      if (box.lo[axis] == box.hi[axis]) {
        if (lo >= first && lo <= last) list.push_back(Event::make(box.lo[axis], kPlanar, local));
        continue;
      }
      if (lo >= first && lo <= last) list.push_back(Event::make(box.lo[axis], kStart, local));
      if (hi >= first && hi <= last) list.push_back(Event::make(box.hi[axis], kEnd, local));
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (boundary[axis] == 0) continue;
    std::vector<Event>& list = scratch.events[axis];
    std::sort(list.begin(), list.end());
    std::uint32_t n_left = 0, n_right = c.count;
    for (int b = 0; b < boundary[axis] - 1; ++b) {
      n_left += scratch.starts[axis * binner.bins + b];
      n_right -= scratch.ends[axis * binner.bins + b];
    }
    sweep_events(c, axis, list, n_left, n_right, best);
  }
}

}  // namespace

SplitPlane find_binned_plane(const SahContext& c, std::span<const Ref> refs, int bins,
                             bool parallel, PlaneScratch& scratch) {
  Binner binner{c.lo, {}, bins};
  for (int axis = 0; axis < 3; ++axis) {
    binner.scale[axis] = c.extent[axis] > 0.f ? static_cast<float>(bins) / c.extent[axis] : 0.f;
  }
  count_all(binner, refs, parallel, scratch);
  // Per axis the best bin boundary, in axis order with a strict comparison (deterministic); then
  // the exact candidates around each axis's best.
  SplitPlane best;
  std::array<int, 3> boundary{0, 0, 0};
  for (int axis = 0; axis < 3; ++axis) {
    if (!(c.extent[axis] > 0.f)) continue;  // a flat cell cannot be split along its flat axis
    SplitPlane axis_best;
    boundary[axis] = best_boundary(c, binner, scratch, axis, axis_best);
    if (axis_best.valid() && (!best.valid() || axis_best.cost < best.cost)) best = axis_best;
  }
  refine(c, binner, refs, boundary, scratch, best);
  return best;
}

}  // namespace cohort::kd
