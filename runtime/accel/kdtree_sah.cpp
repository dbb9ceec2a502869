// The SAH cost of a candidate plane and the exact plane search of Wald & Havran 2006 (their
// FindPlane): one linear sweep per axis over the node's sorted events finds the best of all
// candidate planes (the boundaries of the references' clipped extents).
#include <array>
#include <cmath>
#include <cstddef>

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

void sweep_events(const SahContext& c, int axis, std::span<const Event> events,
                  std::uint32_t n_left, std::uint32_t n_right, SplitPlane& best) {
  // A flat cell cannot be split along its flat axis: both children would be the cell itself.
  if (!(c.extent[axis] > 0.f)) return;
  const AxisSah a = axis_sah(c, axis);
  const std::size_t size = events.size();
  for (std::size_t i = 0; i < size;) {
    // The events at one position, ends before planars before starts (the key's order).
    const std::uint32_t pos_bits = events[i].pos_bits();
    std::array<std::uint32_t, 3> of_type{0, 0, 0};
    for (; i < size && events[i].pos_bits() == pos_bits; ++i) ++of_type[events[i].type()];
    const std::uint32_t ends = of_type[kEnd], planars = of_type[kPlanar], starts = of_type[kStart];
    n_right -= ends + planars;
    evaluate_plane(c, a, Event::float_of(pos_bits), n_left, n_right, planars, best);
    n_left += starts + planars;
  }
}

SplitPlane find_best_plane(const SahContext& context, const EventLists& events) {
  // Axis order and a strict comparison: the same plane whatever the order of the references.
  SplitPlane best;
  for (int axis = 0; axis < 3; ++axis) sweep_events(context, axis, events[axis], 0, context.count, best);
  return best;
}

}  // namespace cohort::kd
