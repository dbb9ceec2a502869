// The SAH cost of a candidate plane and the exact plane search of Wald & Havran 2006 (their
// FindPlane): one linear sweep per axis over the node's sorted extents finds the best of all
// candidate planes (the boundaries of the references' clipped extents).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>


#include "runtime/accel/kdtree/sah.h"
#include "runtime/accel/x86_dispatch.h"

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
COHORT_AVX2_CLONES
void rank_sort(const float* __restrict in, float* __restrict out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const float x = in[i];
    std::uint32_t rank = 0;
    for (std::size_t j = 0; j < i; ++j) rank += in[j] <= x ? 1u : 0u;
    for (std::size_t j = i + 1; j < n; ++j) rank += in[j] < x ? 1u : 0u;
    out[rank] = x;
  }
}

// Sorts v[0, n) in place: std::sort above kRankSort values, else rank_sort.
void sort_floats(float* v, std::size_t n) {
  constexpr std::size_t kRankSort = 48;
  if (n > kRankSort) {
    std::sort(v, v + n);
    return;
  }
  if (n <= 1) return;
  std::array<float, kRankSort> copy;
  std::copy(v, v + n, copy.begin());
  rank_sort(copy.data(), v, n);
}

// Sorts v, every value of which lies in [lo, hi]: the values at either end (the references
// clipped to the cell's faces, often close to half of those the binned search refines) are set
// aside and put back around the sorted rest instead of being sorted with it. The same array as
// sorting all of it.
void sort_floats_within(std::vector<float>& v, float lo, float hi) {
  std::size_t rest = 0, at_lo = 0, at_hi = 0;
  for (const float x : v) {
    const bool low = x == lo, high = !low && x == hi;
    at_lo += low;
    at_hi += high;
    v[rest] = x;  // kept only when neither (branch-free; never ahead of the one read)
    rest += !low && !high;
  }
  sort_floats(v.data(), rest);
  std::copy_backward(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(rest),
                     v.begin() + static_cast<std::ptrdiff_t>(at_lo + rest));
  // The values are +0 where an end is -0 or +0 (AxisExtents::add), so the ends are put back so.
  std::fill_n(v.begin(), at_lo, lo + 0.f);
  std::fill_n(v.begin() + static_cast<std::ptrdiff_t>(at_lo + rest), at_hi, hi + 0.f);
}

}  // namespace

void AxisExtents::sort(float lo, float hi) {
  sort_floats_within(starts, lo, hi);
  sort_floats_within(ends, lo, hi);
  sort_floats_within(flats, lo, hi);
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
COHORT_AVX2_CLONES
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
// candidates compared with one broadcast reference. (With AVX2, count_avx2 runs instead.)
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


// What the search over one axis's candidates found: the least cost and lowest plain cost (with
// the best so far), and the chosen candidate (n: none beats the best so far), with its side of
// the planar references and its plain cost.
struct Pick {
  float least, lowest_plain;
  std::size_t chosen;
  bool chosen_a;
  float plain;
};

// Takes the pick into `best`.
void apply_pick(const Pick& pick, const AxisSah& a, const AxisCandidates& candidates,
                SplitPlane& best) {
  best.lowest_plain_cost = pick.lowest_plain;
  if (pick.chosen == candidates.size) return;
  const std::size_t i = pick.chosen;
  best.axis = a.axis;
  best.pos = candidates.pos[i];
  best.planar_left = pick.chosen_a;
  best.cost = pick.least;
  best.plain_cost = pick.plain;
  best.left_count =
      static_cast<std::uint32_t>(pick.chosen_a ? candidates.left_a[i] : candidates.left_b[i]);
  best.right_count =
      static_cast<std::uint32_t>(pick.chosen_a ? candidates.right_a[i] : candidates.right_b[i]);
}

#if COHORT_X86_DISPATCH
// Up to this many candidates per axis (four vectors of 8) the search runs in AVX2 registers.
constexpr std::size_t kSmallCandidates = 32;

__attribute__((target("avx2"))) inline float horizontal_min(__m256 v) {
  __m128 m = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  m = _mm_min_ps(m, _mm_movehl_ps(m, m));
  m = _mm_min_ss(m, _mm_shuffle_ps(m, m, 1));
  return _mm_cvtss_f32(m);
}

// candidate_costs' arithmetic, operation for operation, on K vectors of 8 held in registers.
template <int K>
__attribute__((target("avx2"))) inline void small_costs(const CostTerms& t, std::size_t n,
                                                       const __m256 (&pos)[K], const float* left,
                                                       const float* right, __m256 (&cost)[K],
                                                       __m256 (&plain)[K]) {
  const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  const __m256 zero = _mm256_setzero_ps(), two = _mm256_set1_ps(2.f);
  const __m256 lo = _mm256_set1_ps(t.lo), hi = _mm256_set1_ps(t.hi);
  const __m256 face = _mm256_set1_ps(t.face), rim = _mm256_set1_ps(t.rim);
  const __m256 inv_area = _mm256_set1_ps(t.inv_area);
  const __m256 k_t = _mm256_set1_ps(t.traversal_cost), k_i = _mm256_set1_ps(t.intersection_cost);
  const __m256 empty_factor = _mm256_set1_ps(t.empty_factor);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int k = 0; k < K; ++k) {
    const __m256 l = _mm256_loadu_ps(left + 8 * k), r = _mm256_loadu_ps(right + 8 * k);
    const __m256 width_left = _mm256_sub_ps(pos[k], lo);
    const __m256 width_right = _mm256_sub_ps(hi, pos[k]);
    const __m256 p_left = _mm256_mul_ps(
        _mm256_mul_ps(two, _mm256_add_ps(face, _mm256_mul_ps(width_left, rim))), inv_area);
    const __m256 p_right = _mm256_mul_ps(
        _mm256_mul_ps(two, _mm256_add_ps(face, _mm256_mul_ps(width_right, rim))), inv_area);
    const __m256 sides = _mm256_add_ps(_mm256_mul_ps(p_left, l), _mm256_mul_ps(p_right, r));
    const __m256 c = _mm256_add_ps(k_t, _mm256_mul_ps(k_i, sides));
    const __m256 empty_left = _mm256_and_ps(_mm256_cmp_ps(l, zero, _CMP_EQ_OQ),
                                            _mm256_cmp_ps(width_left, zero, _CMP_GT_OQ));
    const __m256 empty_right = _mm256_and_ps(_mm256_cmp_ps(r, zero, _CMP_EQ_OQ),
                                             _mm256_cmp_ps(width_right, zero, _CMP_GT_OQ));
    const __m256 empty = _mm256_or_ps(empty_left, empty_right);
    const __m256 valid = _mm256_castsi256_ps(_mm256_cmpgt_epi32(
        _mm256_set1_epi32(static_cast<int>(n)), _mm256_add_epi32(lane, _mm256_set1_epi32(8 * k))));
    const __m256 chosen = _mm256_blendv_ps(c, _mm256_mul_ps(c, empty_factor), empty);
    plain[k] = _mm256_blendv_ps(inf, c, valid);
    cost[k] = _mm256_blendv_ps(inf, chosen, valid);
  }
}

template <int K>
__attribute__((target("avx2"))) inline float small_min(const __m256 (&v)[K]) {
  __m256 m = v[0];
  for (int k = 1; k < K; ++k) m = _mm256_min_ps(m, v[k]);
  return horizontal_min(m);
}

// lowest_at: the first index of the lowest position whose cost is `least` (n: none).
template <int K>
__attribute__((target("avx2"))) inline std::size_t small_lowest_at(const __m256 (&cost)[K],
                                                                  const __m256 (&pos)[K],
                                                                  float least, std::size_t n) {
  const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  const __m256 target = _mm256_set1_ps(least);
  __m256 at[K];
  for (int k = 0; k < K; ++k) {
    at[k] = _mm256_blendv_ps(inf, pos[k], _mm256_cmp_ps(cost[k], target, _CMP_EQ_OQ));
  }
  const __m256 lowest = _mm256_set1_ps(small_min(at));
  unsigned mask = 0;
  for (int k = 0; k < K; ++k) {
    const __m256 hit = _mm256_and_ps(_mm256_cmp_ps(cost[k], target, _CMP_EQ_OQ),
                                     _mm256_cmp_ps(pos[k], lowest, _CMP_EQ_OQ));
    mask |= static_cast<unsigned>(_mm256_movemask_ps(hit)) << (8 * k);
  }
  return mask == 0 ? n : static_cast<std::size_t>(__builtin_ctz(mask));
}

// count_sides and count_planar on K (1-4) vectors of candidates from `first` on, the counts held
// in registers across the references: two operations per vector and reference instead of a
// comparison, a mask and a float addition (count_if). Integers below 2^24 convert to the same
// floats the portable sums give. `flats` are the positions of the references lying flat across
// the axis (none: no planar counts written).
template <int K>
__attribute__((target("avx2"))) inline void count_block(const float* pos, std::size_t n,
                                                        const float* flats, std::size_t n_flats,
                                                        std::size_t first, AxisCandidates& x) {
  const auto [p0, p1, p2, p3] = load_vectors<K>(pos + first);
  const __m256i zero = _mm256_setzero_si256();
  __m256i l0 = zero, l1 = zero, l2 = zero, l3 = zero, r0 = zero, r1 = zero, r2 = zero, r3 = zero;
  for (std::size_t j = 0; j < n; ++j) {
    const __m256 lo = _mm256_broadcast_ss(pos + j), hi = _mm256_broadcast_ss(pos + n + j);
    count_if<_CMP_LT_OQ>(l0, lo, p0);
    count_if<_CMP_GT_OQ>(r0, hi, p0);
    if constexpr (K > 1) {
      count_if<_CMP_LT_OQ>(l1, lo, p1);
      count_if<_CMP_GT_OQ>(r1, hi, p1);
    }
    if constexpr (K > 2) {
      count_if<_CMP_LT_OQ>(l2, lo, p2);
      count_if<_CMP_GT_OQ>(r2, hi, p2);
    }
    if constexpr (K > 3) {
      count_if<_CMP_LT_OQ>(l3, lo, p3);
      count_if<_CMP_GT_OQ>(r3, hi, p3);
    }
  }
  __m256i f0 = zero, f1 = zero, f2 = zero, f3 = zero;
  count_values<K, _CMP_EQ_OQ>(flats, n_flats, p0, p1, p2, p3, f0, f1, f2, f3);
  // As count_planar leaves them: a with the planar references on the left, b on the right.
  const __m256i ls[4] = {l0, l1, l2, l3}, rs[4] = {r0, r1, r2, r3}, fs[4] = {f0, f1, f2, f3};
  for (int k = 0; k < K; ++k) {
    const std::size_t i = first + 8 * static_cast<std::size_t>(k);
    _mm256_storeu_ps(x.left_a.data() + i, _mm256_cvtepi32_ps(_mm256_add_epi32(ls[k], fs[k])));
    _mm256_storeu_ps(x.right_a.data() + i, _mm256_cvtepi32_ps(rs[k]));
    if (n_flats > 0) {
      _mm256_storeu_ps(x.left_b.data() + i, _mm256_cvtepi32_ps(ls[k]));
      _mm256_storeu_ps(x.right_b.data() + i, _mm256_cvtepi32_ps(_mm256_add_epi32(rs[k], fs[k])));
    }
  }
}

// The counts of count_candidates in blocks of four vectors (32 candidates; 12 accumulators and 4
// positions fit the 16 registers), the rest in one smaller block.
__attribute__((target("avx2"))) void count_avx2(const float* pos, std::size_t n,
                                                const float* flats, std::size_t n_flats,
                                                AxisCandidates& x) {
  const std::size_t m = whole_lanes(2 * n);
  std::size_t first = 0;
  for (; first + 4 * kCandidateLanes <= m; first += 4 * kCandidateLanes) {
    count_block<4>(pos, n, flats, n_flats, first, x);
  }
  switch ((m - first) / kCandidateLanes) {
    case 3: count_block<3>(pos, n, flats, n_flats, first, x); break;
    case 2: count_block<2>(pos, n, flats, n_flats, first, x); break;
    case 1: count_block<1>(pos, n, flats, n_flats, first, x); break;
    default: break;
  }
}

// The search of evaluate_candidates on K vectors of candidates held in registers, taken into
// `best` here: returned, the pick went through memory in pieces and the caller's wider loads of
// it waited on those stores (a quarter of evaluate_candidates' own time).
template <int K>
__attribute__((target("avx2"))) void small_search(const CostTerms& t, const AxisSah& a,
                                                  const AxisCandidates& candidates,
                                                  SplitPlane& best) {
  const std::size_t n = candidates.size;
  Pick out{};
  __m256 pos[K], cost_a[K], plain_a[K], cost_b[K] = {}, plain_b[K] = {};  // b only when planar
  for (int k = 0; k < K; ++k) pos[k] = _mm256_loadu_ps(candidates.pos.data() + 8 * k);
  small_costs<K>(t, n, pos, candidates.left_a.data(), candidates.right_a.data(), cost_a, plain_a);
  const bool planar = candidates.planar;
  float least = small_min(cost_a);
  float lowest = std::min(best.lowest_plain_cost, small_min(plain_a));
  if (planar) {
    small_costs<K>(t, n, pos, candidates.left_b.data(), candidates.right_b.data(), cost_b, plain_b);
    least = std::min(least, small_min(cost_b));
    lowest = std::min(lowest, small_min(plain_b));
  }
  out.least = least;
  out.lowest_plain = lowest;
  out.chosen = n;
  if (!best.valid() || least < best.cost) {
    const std::size_t at_a = small_lowest_at(cost_a, pos, least, n);
    const std::size_t at_b = planar ? small_lowest_at(cost_b, pos, least, n) : n;
    const float* p = candidates.pos.data();
    out.chosen_a = at_b == n || (at_a != n && p[at_a] <= p[at_b]);
    out.chosen = out.chosen_a ? at_a : at_b;
    if (out.chosen != n) {
      alignas(32) float plain_lanes[8 * K];
      for (int k = 0; k < K; ++k) {
        _mm256_store_ps(plain_lanes + 8 * k, out.chosen_a ? plain_a[k] : plain_b[k]);
      }
      out.plain = plain_lanes[out.chosen];
    }
  }
  apply_pick(out, a, candidates, best);
}
#endif

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
    if (x.flats.size() < n) x.flats.resize(std::max(n, 2 * x.flats.size()));
    float* flats = x.flats.data();
    std::size_t n_flats = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const float lo = refs[j].box.lo[axis] + 0.f, hi = refs[j].box.hi[axis] + 0.f;
      pos[j] = lo;
      pos[n + j] = hi;
      flats[n_flats] = lo;  // kept when flat
      n_flats += lo == hi;
    }
    x.planar = n_flats > 0;
#if COHORT_X86_DISPATCH
    if (__builtin_cpu_supports("avx2")) {
      count_avx2(pos, n, flats, n_flats, x);
      continue;
    }
#endif
    count_sides(pos, n, x.left_a.data(), x.right_a.data());
    if (x.planar) {
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
  const CostTerms terms{a.lo,     a.hi,           a.face,
                        a.rim,    c.inv_area,     c.traversal_cost,
                        c.intersection_cost, c.empty_factor};
#if COHORT_X86_DISPATCH
  if (n <= kSmallCandidates && __builtin_cpu_supports("avx2")) {
    switch (whole_lanes(n) / kCandidateLanes) {
      case 1: small_search<1>(terms, a, candidates, best); break;
      case 2: small_search<2>(terms, a, candidates, best); break;
      case 3: small_search<3>(terms, a, candidates, best); break;
      default: small_search<4>(terms, a, candidates, best); break;
    }
    return;
  }
#endif
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
  Pick pick{least, lowest, n, true, 0.f};
  if (!best.valid() || least < best.cost) {
    const std::size_t at_a = lowest_at(cost_a, pos, least, n);
    const std::size_t at_b = planar ? lowest_at(cost_b, pos, least, n) : n;
    pick.chosen_a = at_b == n || (at_a != n && pos[at_a] <= pos[at_b]);
    pick.chosen = pick.chosen_a ? at_a : at_b;
    if (pick.chosen != n) pick.plain = pick.chosen_a ? plain_a[pick.chosen] : plain_b[pick.chosen];
  }
  apply_pick(pick, a, candidates, best);
}

void sweep_candidates(const NodeExtents& extents, std::uint32_t count, NodeCandidates& out) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisExtents& x = extents[axis];
    out[axis].clear();
    merge_candidates(x.starts, x.ends, x.flats, 0, count, out[axis]);
  }
}

PlainCostBounds plain_cost_bounds(const SahContext& c, std::span<const Ref> refs) {
  // The three axes at once (lanes x, y, z; the fourth is kept at zero), in float: every term is a
  // sum or product of non-negative values, each rounded once, so the result is within a few ulps.
  using Vec = float __attribute__((vector_size(16)));
  using Lanes = std::int32_t __attribute__((vector_size(16)));
  constexpr Lanes kXyz{-1, -1, -1, 0};
  auto xyz = [](const Vec& v) { return reinterpret_cast<Vec>(reinterpret_cast<Lanes>(v) & kXyz); };
  // A reference's start and end: 16 bytes from its box's lo and from its hi (the fourth lane,
  // hi.x or the triangle index, is cleared before any arithmetic).
  static_assert(offsetof(Ref, box) == 0 && sizeof(Bounds) == 24 && sizeof(Ref) >= 28);
  auto load = [&](const Ref& r, std::size_t offset) {
    Vec v;
    std::memcpy(&v, reinterpret_cast<const char*>(&r) + offset, sizeof v);
    return xyz(v);
  };
  const Vec lo{c.lo.x, c.lo.y, c.lo.z, 0.f}, hi{c.hi.x, c.hi.y, c.hi.z, 0.f};
  const Vec extent{c.extent.x, c.extent.y, c.extent.z, 0.f};
  const Vec extent_u{c.extent.y, c.extent.z, c.extent.x, 0.f};  // the two other axes of each
  const Vec extent_v{c.extent.z, c.extent.x, c.extent.y, 0.f};
  const Vec face = extent_u * extent_v, rim = extent_u + extent_v;
  // Per axis, the sum over references of the narrower of the two cells a plane must leave each in:
  // [lo, its end] when it goes left, [its start, hi] when it goes right (a straddling one is in
  // both, whose probabilities sum to at least 1, the most a width clamped to the cell gives).
  Vec widths{}, first = hi, last = lo;  // and where the references start and end
  for (const Ref& r : refs) {
    const Vec start = load(r, 0), end = load(r, 12);
    const Vec left = end - lo, right = hi - start;
    const Vec narrower = left < right ? left : right;
    widths += narrower < extent ? narrower : extent;
    first = start < first ? start : first;
    last = end > last ? end : last;
  }
  const float n = static_cast<float>(refs.size());
  const float scale = 2.f * c.intersection_cost * c.inv_area;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  constexpr Vec kNone{kInf, kInf, kInf, kInf};
  const Vec any = kXyz ? c.traversal_cost + scale * (n * face + widths * rim) : kNone;
  // The only empty cuts: the planes where the references start and end, every reference on the
  // other side, when the empty side has width (Wald & Havran's lambda; never in the fourth lane).
  const Vec cut_first = c.traversal_cost + scale * n * (face + (hi - first) * rim);
  const Vec cut_last = c.traversal_cost + scale * n * (face + (last - lo) * rim);
  const Vec first_cut = first > lo ? cut_first : kNone, last_cut = last < hi ? cut_last : kNone;
  const Vec empty_cut = first_cut < last_cut ? first_cut : last_cut;
  auto least = [](const Vec& v) { return std::min(std::min(v[0], v[1]), std::min(v[2], v[3])); };
  return {least(any), least(empty_cut)};
}

// From bounds of the costs (plain_cost_bounds), the chosen plane's plain cost exceeds K_I N:
// - when no plane's plain cost can reach K_I N;
// - when an empty cut's cost with the bonus beats every other plane's and yet no empty cut's plain
//   cost reaches K_I N: the chosen plane is then an empty cut (where most small nodes of the
//   compact tree end as leaves).
// Each comparison keeps a margin far wider than the float rounding of the search's costs, so the
// tree is the one the search would have given.
bool split_cannot_pay(const SahContext& context, std::span<const Ref> refs) {
  constexpr double kMargin = 1e-4;
  const double leaf_cost =
      static_cast<double>(context.intersection_cost * static_cast<float>(refs.size()));
  const PlainCostBounds bounds = plain_cost_bounds(context, refs);
  if (bounds.any * (1.0 - kMargin) > leaf_cost) return true;
  const double empty_factor = context.empty_factor;
  return empty_factor < 1.0 && bounds.empty_cut * (1.0 - kMargin) > leaf_cost &&
         bounds.any * (1.0 - kMargin) > bounds.empty_cut * empty_factor * (1.0 + kMargin);
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
