// The SAH of the KD-tree build: split planes and their cost, the candidate planes of the exact
// search (Wald & Havran, "On building fast kd-trees for ray tracing, and on doing that in
// O(N log N)", IEEE RT 2006), counted directly for small nodes or swept over sorted extents
// (sah_exact.cpp), and the binned search of large nodes (sah_binned.cpp). Internal to
// runtime/accel/kdtree.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/accel/kdtree/references.h"
#include "runtime/scene/bounds.h"

namespace cohort::kd {

struct SplitPlane {
  int axis = -1;  // -1: no candidate
  float pos = 0.f;
  bool planar_left = true;  // where triangles lying in the plane go
  float cost = 0.f;        // SAH with the empty-space bonus: what chooses the plane
  float plain_cost = 0.f;  // the same without the bonus
  // The lowest plain cost of every candidate the search evaluated (not only of the chosen one):
  // whether splitting pays at all (see KdBuildOptions::plain_sah_triangles).
  float lowest_plain_cost = std::numeric_limits<float>::infinity();
  std::uint32_t left_count = 0;  // references on each side, as the search counted them
  std::uint32_t right_count = 0;
  bool valid() const { return axis >= 0; }
};

// What every candidate plane of one node shares.
struct SahContext {
  glm::vec3 lo, hi, extent;
  float inv_area;  // 1 / surface area of the cell
  float traversal_cost;
  float intersection_cost;
  float empty_factor;   // 1 - empty_bonus
  std::uint32_t count;  // references in the node
};

// False for a cell without area (nothing to split), with an infinite one, or with one too small
// for 1 / area to be finite.
bool make_sah_context(const Bounds& voxel, std::size_t count, const KdBuildOptions& options,
                      SahContext& out);

// Wald & Havran's C_V(p) with their lambda(p): cutting off empty space is rewarded, but only when
// the empty side has volume, otherwise every flat cut at the cell boundary would look like a win.
// `plain` gets the cost without the bonus.
inline float plane_cost(const SahContext& c, float p_left, float p_right, std::uint32_t n_left,
                        std::uint32_t n_right, float width_left, float width_right, float& plain) {
  plain = c.traversal_cost + c.intersection_cost * (p_left * static_cast<float>(n_left) +
                                                    p_right * static_cast<float>(n_right));
  const bool empty_cut = (n_left == 0 && width_left > 0.f) || (n_right == 0 && width_right > 0.f);
  return empty_cut ? plain * c.empty_factor : plain;
}

// Keeps the cheaper of `best` and `other` (ties keep `best`) and the lowest plain cost of both.
inline void keep_better(SplitPlane& best, const SplitPlane& other) {
  const float lowest = std::min(best.lowest_plain_cost, other.lowest_plain_cost);
  if (other.valid() && (!best.valid() || other.cost < best.cost)) best = other;
  best.lowest_plain_cost = lowest;
}

// The parts of a candidate's cost that depend only on its axis.
struct AxisSah {
  int axis;
  float lo, hi;  // the cell along the axis
  float face;    // area of the cell's face across the axis
  float rim;     // the two other extents, summed
};

inline AxisSah axis_sah(const SahContext& c, int axis) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  return {axis, c.lo[axis], c.hi[axis], c.extent[u] * c.extent[v], c.extent[u] + c.extent[v]};
}

// Evaluates plane `pos` both with the planar triangles on the left and on the right (Wald & Havran's
// SAH(p, V, N_L, N_R, N_P)), keeping the cheaper; ties keep the earlier candidate, so the order of
// the candidates alone decides and the result is deterministic. Inline: the searches call it once
// per candidate.
inline void evaluate_plane(const SahContext& c, const AxisSah& a, float pos, std::uint32_t n_left,
                           std::uint32_t n_right, std::uint32_t n_planar, SplitPlane& best) {
  const float width_left = pos - a.lo, width_right = a.hi - pos;
  const float p_left = 2.f * (a.face + width_left * a.rim) * c.inv_area;
  const float p_right = 2.f * (a.face + width_right * a.rim) * c.inv_area;
  auto consider = [&](std::uint32_t l, std::uint32_t r, bool planar_left) {
    float plain;
    const float cost = plane_cost(c, p_left, p_right, l, r, width_left, width_right, plain);
    const float lowest = std::min(best.lowest_plain_cost, plain);
    if (!best.valid() || cost < best.cost) best = {a.axis, pos, planar_left, cost, plain, lowest, l, r};
    best.lowest_plain_cost = lowest;
  };
  consider(n_left + n_planar, n_right, true);
  if (n_planar > 0) consider(n_left, n_right + n_planar, false);
}

// Candidates are counted and evaluated a vector of this many at a time, with no scalar tail.
constexpr std::size_t kCandidateLanes = 8;

// n rounded up to whole vectors of kCandidateLanes.
constexpr std::size_t whole_lanes(std::size_t n) {
  return (n + kCandidateLanes - 1) / kCandidateLanes * kCandidateLanes;
}

// One axis's candidate planes in ascending order with the counts Wald & Havran's sweep gives each:
// references entirely left of the plane, reaching right of it, and lying in it. They depend on the
// references only, not on the cell, so a child that gets every reference unchanged (an empty-space
// cut) evaluates its parent's candidates again in its own cell without sorting or merging.
// Each candidate is evaluated twice, with the planar references on the left (a) and on the right
// (b); the counts are floats, as the SAH uses them (exact below 2^24), so the evaluation is a
// plain loop the compiler vectorises.
struct AxisCandidates {
  std::vector<float> pos;
  std::vector<float> left_a, right_a, left_b, right_b;
  std::size_t size = 0;
  bool planar = false;  // some candidate has planar references (else b equals a)
  std::vector<float> flats;  // count_candidates' working memory: where flat references lie

  void clear() {
    size = 0;
    planar = false;
  }
  // Room for `more` candidates after the first `size`, rounded up to whole vectors of
  // kCandidateLanes: the counting and the evaluation read and write whole vectors (the lanes past
  // the candidates hold finite stale values and are ignored).
  void reserve_more(std::size_t more) {
    const std::size_t needed = whole_lanes(size + more);
    if (pos.size() < needed) {
      for (std::vector<float>* v : {&pos, &left_a, &right_a, &left_b, &right_b}) {
        v->resize(std::max(needed, 2 * v->size()));
      }
    }
  }
};

using NodeCandidates = std::array<AxisCandidates, 3>;

// Wald & Havran's incremental sweep over one axis's sorted extents, starting from n_left references
// entirely before the first position and n_right reaching past it: at each position the extents
// ending there leave the right side, the flat ones sit in the plane, and those starting there join
// the left side. Appends the candidates to `out` (sah_exact.cpp).
void merge_candidates(std::span<const float> starts, std::span<const float> ends,
                      std::span<const float> flats, std::uint32_t n_left, std::uint32_t n_right,
                      AxisCandidates& out);

// The candidates of a small node counted directly instead of swept: each boundary of a
// reference's extent with the references starting before it, ending after it and lying in it,
// from comparisons with every reference (n^2 of them, branch-free and vectorised), in no order and
// with repeats. Below a few dozen references this costs less than sorting and merging, and it
// gives the counts the sweep gives, so evaluate_candidates chooses the same plane (sah_exact.cpp).
void count_candidates(std::span<const Ref> refs, NodeCandidates& out);

// evaluate_plane over the candidates of `axis` in ascending order of position: the same plane
// (first of the cheapest) and lowest plain cost whatever the candidates' order and repeats,
// computed a vector of candidates at a time (sah_exact.cpp).
void evaluate_candidates(const SahContext& c, int axis, const AxisCandidates& candidates,
                         std::vector<float>& costs, SplitPlane& best);

// Working memory of the plane searches, reused from node to node by one task.
struct PlaneScratch {
  std::vector<std::uint32_t> starts, ends;  // binned counts, [axis * bins + bin]
  std::vector<std::uint8_t> refined;        // 1 for the bins the exact sweep covers, same index
  // Per reference: start and end bin of each axis (a cleared array cost the root's count a serial
  // pass over 13 MB of fresh pages for Sponza x4).
  UninitialisedArray<std::uint16_t> ref_bins;
  // The refinement's gathering of every extent end, 9 per reference, before it keeps those in the
  // refined bins (a cleared vector cost 2.4% of the build in memset).
  UninitialisedArray<float> gathered;
  NodeExtents extents;
  NodeCandidates candidates;
  std::vector<float> costs;  // evaluate_candidates' working memory
  // Tests: the refined bins' candidates always sorted and swept, never counted (the two must agree).
  bool sweep_refined = false;
};

// Wald & Havran's sweep (their FindPlane) over a node of `count` references' sorted extents:
// every boundary of a reference's extent is a candidate, with its counts (sah_exact.cpp).
void sweep_candidates(const NodeExtents& extents, std::uint32_t count, NodeCandidates& out);

// The best plane of a node's candidates, swept or counted (sah_exact.cpp). They are kept for a
// child that inherits them.
SplitPlane find_best_plane(const SahContext& context, const NodeCandidates& candidates,
                           std::vector<float>& costs);

// The best of `bins - 1` evenly spaced planes per axis, counted from binned reference extents in
// time linear in the node, and of the exact candidates inside the two bins around each axis's best
// boundary (sah_binned.cpp). For large nodes, where sorting every extent would dominate the
// build.
SplitPlane find_binned_plane(const SahContext& context, std::span<const Ref> refs, int bins,
                             bool parallel, PlaneScratch& scratch);

// What the plain SAH cost (K_T + K_I (P_L N_L + P_R N_R)) of a node's planes can be, without
// searching them (sah_exact.cpp):
// - `any`: a lower bound for every plane through the cell. A reference going left lies in
//   [lo, plane], so P_L is at least that of the cell cut at its end, and likewise on the right.
// - `empty_cut`: the least plain cost of the candidates that cut off empty space (the planes where
//   the references start or end; infinite when they reach every face of the cell).
// Computed in float: every term is a sum or product of non-negative values, so these are within
// a few ulps of the exact bounds, as the search's costs are of the exact costs.
struct PlainCostBounds {
  double any = std::numeric_limits<double>::infinity();
  double empty_cut = std::numeric_limits<double>::infinity();
};
PlainCostBounds plain_cost_bounds(const SahContext& context, std::span<const Ref> refs);

// Whether the compact criterion for small nodes (split only when the chosen plane's plain cost is
// at most K_I N) makes a node of these references a leaf whatever plane the search finds, from
// plain_cost_bounds (sah_exact.cpp).
bool split_cannot_pay(const SahContext& context, std::span<const Ref> refs);

}  // namespace cohort::kd
