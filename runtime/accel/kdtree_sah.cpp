// The SAH cost of a candidate plane and the exact plane search of Wald & Havran 2006 (their
// FindPlane): one linear sweep per axis over the node's sorted extents finds the best of all
// candidate planes (the boundaries of the references' clipped extents).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {
bool make_sah_context(const Bounds& voxel, std::size_t count, const KdBuildOptions& options,
                      SahContext& out) {
  const float area = voxel.surface_area();
  // 1 / area finite too (a cell of denormal area has none): then every candidate's cost is
  // finite, which the plane searches rely on.
  if (!(area > 0.f) || !std::isfinite(area) || !std::isfinite(1.f / area)) return false;
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

namespace {

// Sorting by rank: each value goes where the count of smaller values (and of equal ones before
// it) puts it. Quadratic, but without a data-dependent branch: the comparisons vectorise, where a
// comparison sort of the small arrays of the exact sweep mispredicts about every other branch
// (the sort was the build's largest share of time). The result is the sorted array, as std::sort
// gives it (equal floats are the same bits: -0 was made +0).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void rank_sort(const float* __restrict in, float* __restrict out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const float x = in[i];
    std::uint32_t rank = 0;
    for (std::size_t j = 0; j < i; ++j) rank += in[j] <= x ? 1u : 0u;
    for (std::size_t j = i + 1; j < n; ++j) rank += in[j] < x ? 1u : 0u;
    out[rank] = x;
  }
}

void sort_floats(std::vector<float>& v) {
  constexpr std::size_t kRankSort = 48;
  if (v.size() > kRankSort) {
    std::sort(v.begin(), v.end());
    return;
  }
  if (v.size() <= 1) return;
  std::array<float, kRankSort> copy;
  std::copy(v.begin(), v.end(), copy.begin());
  rank_sort(copy.data(), v.data(), v.size());
}

}  // namespace

void AxisExtents::sort() {
  sort_floats(starts);
  sort_floats(ends);
  sort_floats(flats);
}

namespace {

// How many of the sorted values from `i` on equal `pos`; advances `i` past them.
std::uint32_t take_equal(std::span<const float> sorted, std::size_t& i, float pos) {
  const std::size_t first = i;
  while (i < sorted.size() && sorted[i] == pos) ++i;
  return static_cast<std::uint32_t>(i - first);
}

// evaluate_plane's arithmetic, term for term, for n candidates and both sides of their planar
// references. Restrict parameters (the outputs alias no input) and no branch, so GCC vectorises it.
struct CostTerms {
  float lo, hi, face, rim, inv_area, traversal_cost, intersection_cost, empty_factor;
};

// On x86 with GCC also compiled for AVX2 (8 candidates a vector), chosen at load time; AVX2 alone
// does not enable fused multiply-add, so both versions compute the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void candidate_costs(CostTerms t, std::size_t n, const float* __restrict pos,
                     const float* __restrict left, const float* __restrict right,
                     float* __restrict cost, float* __restrict plain) {
  constexpr float kNone = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < whole_lanes(n); ++i) {
    const float width_left = pos[i] - t.lo, width_right = t.hi - pos[i];
    const float p_left = 2.f * (t.face + width_left * t.rim) * t.inv_area;
    const float p_right = 2.f * (t.face + width_right * t.rim) * t.inv_area;
    const float c = t.traversal_cost + t.intersection_cost * (p_left * left[i] + p_right * right[i]);
    // Bitwise, not short-circuit, and both products taken: a select, not a branch.
    const bool empty =
        ((left[i] == 0.f) & (width_left > 0.f)) | ((right[i] == 0.f) & (width_right > 0.f));
    const float bonus = c * t.empty_factor;
    // The lanes past the candidates never win.
    plain[i] = i < n ? c : kNone;
    cost[i] = i < n ? (empty ? bonus : c) : kNone;
  }
}

// The least of value(i) over whole_lanes(n) indices: an element-wise minimum over vectors, then
// across one vector, instead of a chain of scalar minima. (Unrolled, GCC's vectoriser leaves the
// lane loop scalar; as a loop it takes it a vector at a time.)
template <typename Value>
float least_over_lanes(std::size_t n, Value value) {
  float lane[kCandidateLanes];
  std::fill(lane, lane + kCandidateLanes, std::numeric_limits<float>::infinity());
  for (std::size_t k = 0; k < whole_lanes(n); k += kCandidateLanes) {
#pragma GCC unroll 1
    for (std::size_t l = 0; l < kCandidateLanes; ++l) {
      const float v = value(k + l);
      lane[l] = v < lane[l] ? v : lane[l];
    }
  }
  return *std::min_element(lane, lane + kCandidateLanes);
}

float least_of(const float* values, std::size_t n) {
  return least_over_lanes(n, [values](std::size_t i) { return values[i]; });
}

// The first index of the lowest position whose cost is `least` (n: none), its position found the
// same way (cost and position both loaded before the select, so it is a select, not a branch).
std::size_t lowest_at(const float* cost, const float* pos, float least, std::size_t n) {
  const float lowest = least_over_lanes(n, [&](std::size_t i) {
    const float c = cost[i], p = pos[i];
    return c == least ? p : std::numeric_limits<float>::infinity();
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (cost[i] == least && pos[i] == lowest) return i;
  }
  return n;
}

// count_candidates' comparisons: for each of the 2n candidates pos[i] (the n low ends, then the
// n high ends), the references starting before it (left) and ending after it (right). Written
// over the candidates, with the references in the outer loop, so the inner loop is a vector of
// candidates compared with one broadcast reference.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void count_sides(const float* __restrict pos, std::size_t n, float* __restrict left,
                 float* __restrict right) {
  const std::size_t m = whole_lanes(2 * n);
  for (std::size_t i = 0; i < m; ++i) left[i] = right[i] = 0.f;
  for (std::size_t j = 0; j < n; ++j) {
    const float lo = pos[j], hi = pos[n + j];
    for (std::size_t i = 0; i < m; ++i) {
      left[i] += lo < pos[i] ? 1.f : 0.f;
      right[i] += hi > pos[i] ? 1.f : 0.f;
    }
  }
}

// The references lying flat in each candidate's plane, on the left (a) or on the right (b), as
// merge_candidates counts them; `left_a` and `right_a` come in as count_sides left them.
void count_planar(const float* pos, std::size_t n, float* left_a, const float* right_a,
                  float* left_b, float* right_b) {
  const std::size_t m = 2 * n;
  for (std::size_t i = 0; i < m; ++i) {
    left_b[i] = left_a[i];
    right_b[i] = right_a[i];
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (pos[j] != pos[n + j]) continue;
    for (std::size_t i = 0; i < m; ++i) {
      const float in_plane = pos[j] == pos[i] ? 1.f : 0.f;
      left_a[i] += in_plane;
      right_b[i] += in_plane;
    }
  }
}

}  // namespace

void merge_candidates(std::span<const float> starts, std::span<const float> ends,
                      std::span<const float> flats, std::uint32_t n_left, std::uint32_t n_right,
                      AxisCandidates& out) {
  out.reserve_more(starts.size() + ends.size() + flats.size());
  std::size_t n = out.size;
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
    out.pos[n] = pos;
    out.left_a[n] = static_cast<float>(n_left + flat);
    out.right_a[n] = static_cast<float>(n_right);
    out.left_b[n] = static_cast<float>(n_left);
    out.right_b[n] = static_cast<float>(n_right + flat);
    out.planar |= flat > 0;
    ++n;
    n_left += starting + flat;
  }
  out.size = n;
}

void count_candidates(std::span<const Ref> refs, NodeCandidates& out) {
  const std::size_t n = refs.size();
  for (int axis = 0; axis < 3; ++axis) {
    AxisCandidates& x = out[axis];
    x.clear();
    x.reserve_more(2 * n);
    x.size = 2 * n;
    // The candidates: every reference's low end, then every high end (a flat extent gives the
    // same position twice; a duplicate counts the same and loses the tie to its twin).
    float* pos = x.pos.data();
    bool planar = false;
    for (std::size_t j = 0; j < n; ++j) {
      const float lo = refs[j].box.lo[axis] + 0.f, hi = refs[j].box.hi[axis] + 0.f;
      pos[j] = lo;
      pos[n + j] = hi;
      planar |= lo == hi;
    }
    count_sides(pos, n, x.left_a.data(), x.right_a.data());
    x.planar = planar;
    if (planar) {
      count_planar(pos, n, x.left_a.data(), x.right_a.data(), x.left_b.data(), x.right_b.data());
    }
  }
}

void evaluate_candidates(const SahContext& c, int axis, const AxisCandidates& candidates,
                         std::vector<float>& costs, SplitPlane& best) {
  // A flat cell cannot be split along its flat axis: both children would be the cell itself.
  const std::size_t n = candidates.size;
  if (!(c.extent[axis] > 0.f) || n == 0) return;
  const AxisSah a = axis_sah(c, axis);
  // evaluate_plane's arithmetic, term for term, for every candidate and both sides of the planar
  // references, in whole vectors (`lanes`, the ones past n costing infinity): costs planar left,
  // then planar right, then the plain costs likewise. Without planar references b is a copy of a,
  // which never beats it (a comes first).
  const std::size_t lanes = whole_lanes(n);
  if (costs.size() < 4 * lanes) costs.resize(std::max(4 * lanes, 2 * costs.size()));
  float* cost_a = costs.data();
  float* cost_b = cost_a + lanes;
  float* plain_a = cost_b + lanes;
  float* plain_b = plain_a + lanes;
  const float* pos = candidates.pos.data();
  const CostTerms terms{a.lo,           a.hi,           a.face,
                        a.rim,          c.inv_area,     c.traversal_cost,
                        c.intersection_cost, c.empty_factor};
  candidate_costs(terms, n, pos, candidates.left_a.data(), candidates.right_a.data(), cost_a,
                  plain_a);
  if (candidates.planar) {
    candidate_costs(terms, n, pos, candidates.left_b.data(), candidates.right_b.data(), cost_b,
                    plain_b);
  } else {  // no planar references: b would be a copy of a
    cost_b = cost_a;
    plain_b = plain_a;
  }
  // evaluate_plane's comparisons in the order of the ascending sweep (by position, planar left
  // before planar right at one position): the first of the cheapest wins, and an invalid best
  // takes the first candidate whatever its cost. Costs are finite (make_sah_context), so that is
  // the least cost, then the lowest position at that cost; a tie with an earlier axis's plane
  // keeps that plane. Found by vector minima (a search for a running minimum mispredicts at every
  // new one), and by position rather than index, so counted candidates (any order, repeated
  // positions) choose what the sweep does.
  const bool planar = candidates.planar;
  float least = least_of(cost_a, n);
  float lowest = std::min(best.lowest_plain_cost, least_of(plain_a, n));
  if (planar) {
    least = std::min(least, least_of(cost_b, n));
    lowest = std::min(lowest, least_of(plain_b, n));
  }
  std::size_t chosen = n;  // none of these
  bool chosen_a = true;
  float chosen_cost = best.cost;
  if (!best.valid() || least < best.cost) {
    const std::size_t at_a = lowest_at(cost_a, pos, least, n);
    const std::size_t at_b = planar ? lowest_at(cost_b, pos, least, n) : n;
    chosen_a = at_b == n || (at_a != n && pos[at_a] <= pos[at_b]);
    chosen = chosen_a ? at_a : at_b;
    chosen_cost = least;
  }
  best.lowest_plain_cost = lowest;
  if (chosen == n) return;
  best.axis = a.axis;
  best.pos = pos[chosen];
  best.planar_left = chosen_a;
  best.cost = chosen_cost;
  best.plain_cost = chosen_a ? plain_a[chosen] : plain_b[chosen];
  best.left_count =
      static_cast<std::uint32_t>(chosen_a ? candidates.left_a[chosen] : candidates.left_b[chosen]);
  best.right_count = static_cast<std::uint32_t>(chosen_a ? candidates.right_a[chosen]
                                                         : candidates.right_b[chosen]);
}

void sweep_candidates(const NodeExtents& extents, std::uint32_t count, NodeCandidates& out) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisExtents& x = extents[axis];
    out[axis].clear();
    merge_candidates(x.starts, x.ends, x.flats, 0, count, out[axis]);
  }
}

SplitPlane find_best_plane(const SahContext& context, const NodeCandidates& candidates,
                           std::vector<float>& costs) {
  // Axis order and a strict comparison: the same plane whatever the order of the references.
  SplitPlane best;
  for (int axis = 0; axis < 3; ++axis) {
    evaluate_candidates(context, axis, candidates[axis], costs, best);
  }
  return best;
}

}  // namespace cohort::kd
