// The SAH cost of a candidate plane and the exact plane search of Wald & Havran 2006 (their
// FindPlane): one linear sweep per axis over the node's sorted extents finds the best of all
// candidate planes (the boundaries of the references' clipped extents).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
bool make_sah_context(const Bounds& voxel, std::size_t count, const KdBuildOptions& options,
                      SahContext& out) {
  const float area = voxel.surface_area();
  if (!(area > 0.f) || !std::isfinite(area)) return false;
  out = {voxel.lo,
         voxel.hi,
         voxel.extent(),
         1.f / area,
         options.traversal_cost,
         options.intersection_cost,
         1.f - options.empty_bonus,
         static_cast<std::uint32_t>(count)};
  return true;
}

void AxisExtents::sort() {
  std::sort(starts.begin(), starts.end());
  std::sort(ends.begin(), ends.end());
  std::sort(flats.begin(), flats.end());
}

namespace {

// How many of the sorted values from `i` on equal `pos`; advances `i` past them.
std::uint32_t take_equal(std::span<const float> sorted, std::size_t& i, float pos) {
  const std::size_t first = i;
  while (i < sorted.size() && sorted[i] == pos) ++i;
  return static_cast<std::uint32_t>(i - first);
}

}  // namespace

void sweep_extents(const SahContext& c, int axis, std::span<const float> starts,
                   std::span<const float> ends, std::span<const float> flats, std::uint32_t n_left,
                   std::uint32_t n_right, SplitPlane& best) {
  // A flat cell cannot be split along its flat axis: both children would be the cell itself.
  if (!(c.extent[axis] > 0.f)) return;
  const AxisSah a = axis_sah(c, axis);
  std::size_t s = 0, e = 0, f = 0;
  while (s < starts.size() || e < ends.size() || f < flats.size()) {
    // The next position of any of the three: the candidates in ascending order.
    float pos = std::numeric_limits<float>::infinity();
    if (s < starts.size()) pos = starts[s];
    if (e < ends.size()) pos = std::min(pos, ends[e]);
    if (f < flats.size()) pos = std::min(pos, flats[f]);
    const std::uint32_t ending = take_equal(ends, e, pos);
    const std::uint32_t flat = take_equal(flats, f, pos);
    const std::uint32_t starting = take_equal(starts, s, pos);
    n_right -= ending + flat;
    evaluate_plane(c, a, pos, n_left, n_right, flat, best);
    n_left += starting + flat;
  }
}

SplitPlane find_best_plane(const SahContext& context, const NodeExtents& extents) {
  // Axis order and a strict comparison: the same plane whatever the order of the references.
  SplitPlane best;
  for (int axis = 0; axis < 3; ++axis) {
    const AxisExtents& x = extents[axis];
    sweep_extents(context, axis, x.starts, x.ends, x.flats, 0, context.count, best);
  }
  return best;
}

}  // namespace cohort::kd
