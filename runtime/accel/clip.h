// Clipping a triangle to an axis-aligned box, for the "perfect splits" of the SAH KD-tree build
// (Havran's thesis, "Heuristic Ray Shooting Algorithms", 2000; Wald & Havran 2006): a triangle that
// straddles a split plane is registered in a child only with the bounds of its part inside that
// child's cell, so the SAH sees its true extent and later splits do not drag it into cells it never
// reaches.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "runtime/scene/bounds.h"

namespace cohort::kd {

// Bounds of (triangle a, b, c) intersected with `box` (closed), or an empty Bounds when they do not
// meet. Conservative: computed in double and rounded outward to float, then clamped to `box`, so
// the result contains every float point of the triangle inside the box and lies inside the box.
// A triangle that only touches the box (a vertex or an edge on a face) yields a flat, non-empty
// box.
Bounds clip_triangle_bounds(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                            const Bounds& box);

// clip_triangle_bounds on the two halves of `cell` split at x[axis] = pos ({lower, upper}), with
// the clipping to the cell done once for both: what a KD-tree split needs for a straddling
// triangle. `extent` contains the triangle's part in the cell (a KD reference's box; the cell
// itself where nothing tighter is known): a cell face it does not reach cannot cut that convex
// part, so that face's plane gets no clipping pass (on Sponza x4 18 % of the passes). The
// order of the clipping planes differs, and skipped planes move crossings to other edges, so the
// boxes may differ from the one-cell function in the last bit, but they are just as conservative.
// On x86 with AVX2 a vector version runs, which gives the same bits as this portable one (kept
// public for the test that checks it).
std::array<Bounds, 2> split_triangle_bounds(const glm::vec3& a, const glm::vec3& b,
                                            const glm::vec3& c, const Bounds& cell,
                                            const Bounds& extent, int axis, float pos);
std::array<Bounds, 2> split_triangle_bounds_portable(const glm::vec3& a, const glm::vec3& b,
                                                     const glm::vec3& c, const Bounds& cell,
                                                     const Bounds& extent, int axis, float pos);

}  // namespace cohort::kd
