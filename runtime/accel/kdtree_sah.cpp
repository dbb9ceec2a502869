// The SAH plane search of Wald & Havran 2006 (their FindPlane): one linear sweep per axis over
// the node's sorted events finds the best of all candidate planes (the triangles' clipped extents).
#include <tbb/parallel_invoke.h>

#include <cmath>
#include <cstddef>
#include <limits>

#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
namespace {

// What every candidate of one node shares.
struct SahContext {
  glm::vec3 lo, hi, extent;
  float inv_area;  // 1 / surface area of the cell
  float traversal_cost;
  float intersection_cost;
  float empty_factor;   // 1 - empty_bonus
  std::uint32_t count;  // triangles in the node
};

// Wald & Havran's C_V(p) with their lambda(p): cutting off empty space is rewarded, but only when
// the empty side has volume, otherwise every flat cut at the cell boundary would look like a win.
float plane_cost(const SahContext& c, float p_left, float p_right, std::uint32_t n_left,
                 std::uint32_t n_right, float width_left, float width_right) {
  float cost = c.traversal_cost + c.intersection_cost * (p_left * static_cast<float>(n_left) +
                                                         p_right * static_cast<float>(n_right));
  const bool empty_cut = (n_left == 0 && width_left > 0.f) || (n_right == 0 && width_right > 0.f);
  return empty_cut ? cost * c.empty_factor : cost;
}

// Evaluates plane `pos` both with the planar triangles on the left and on the right (their
// SAH(p, V, N_L, N_R, N_P)), keeping the cheaper; ties keep the earlier candidate, so the sweep
// order alone decides and the result is deterministic.
void evaluate(const SahContext& c, int axis, float pos, std::uint32_t n_left, std::uint32_t n_right,
              std::uint32_t n_planar, SplitPlane& best) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const float face = c.extent[u] * c.extent[v];
  const float rim = c.extent[u] + c.extent[v];
  const float width_left = pos - c.lo[axis], width_right = c.hi[axis] - pos;
  const float p_left = 2.f * (face + width_left * rim) * c.inv_area;
  const float p_right = 2.f * (face + width_right * rim) * c.inv_area;
  auto consider = [&](std::uint32_t l, std::uint32_t r, bool planar_left) {
    const float cost = plane_cost(c, p_left, p_right, l, r, width_left, width_right);
    if (!best.valid() || cost < best.cost) best = {axis, pos, planar_left, cost, l, r};
  };
  consider(n_left + n_planar, n_right, true);
  if (n_planar > 0) consider(n_left, n_right + n_planar, false);
}

// Wald & Havran's sweep for one axis: at each position, the end events leave the right side, the
// planar ones sit in the plane, and the start events join the left side after the evaluation.
SplitPlane sweep_axis(const SahContext& c, int axis, const std::vector<Event>& events) {
  SplitPlane best;
  // A flat cell cannot be split along its flat axis: both children would be the cell itself.
  if (!(c.extent[axis] > 0.f)) return best;
  std::uint32_t n_left = 0, n_right = c.count;
  const std::size_t size = events.size();
  for (std::size_t i = 0; i < size;) {
    const float pos = events[i].pos;
    std::uint32_t ends = 0, planars = 0, starts = 0;
    for (; i < size && events[i].pos == pos && events[i].type() == kEnd; ++i) ++ends;
    for (; i < size && events[i].pos == pos && events[i].type() == kPlanar; ++i) ++planars;
    for (; i < size && events[i].pos == pos && events[i].type() == kStart; ++i) ++starts;
    n_right -= ends + planars;
    evaluate(c, axis, pos, n_left, n_right, planars, best);
    n_left += starts + planars;
  }
  return best;
}

}  // namespace

SplitPlane find_best_plane(const NodeWork& work, const KdBuildOptions& options, bool parallel) {
  const float area = work.voxel.surface_area();
  if (!(area > 0.f) || !std::isfinite(area)) return {};
  const SahContext context{work.voxel.lo,
                           work.voxel.hi,
                           work.voxel.extent(),
                           1.f / area,
                           options.traversal_cost,
                           options.intersection_cost,
                           1.f - options.empty_bonus,
                           static_cast<std::uint32_t>(work.tris.size())};
  std::array<SplitPlane, 3> per_axis;
  auto sweep = [&](int axis) { per_axis[axis] = sweep_axis(context, axis, work.events[axis]); };
  if (parallel) {
    tbb::parallel_invoke([&] { sweep(0); }, [&] { sweep(1); }, [&] { sweep(2); });
  } else {
    for (int axis = 0; axis < 3; ++axis) sweep(axis);
  }
  // Combined in axis order with a strict comparison: the same plane whatever the thread timing.
  SplitPlane best;
  for (const SplitPlane& candidate : per_axis) {
    if (candidate.valid() && (!best.valid() || candidate.cost < best.cost)) best = candidate;
  }
  return best;
}

}  // namespace cohort::kd
