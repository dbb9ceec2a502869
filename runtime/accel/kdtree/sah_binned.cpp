// Binned SAH plane search for large nodes (Wald 2007 for BVHs; Shevtsov et al. 2007 and Hunt et
// al. 2006 for KD-trees): every reference adds its start to the bin of its lower bound and its end
// to the bin of its upper bound; prefix sums over the bins then give, for each bin boundary, how
// many references reach left of it and how many right of it. The counts are integers, so a
// parallel count gives the same plane as a serial one.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <utility>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>


#include "runtime/accel/kdtree/sah.h"
#include "runtime/accel/x86_dispatch.h"

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

// Counts the references' bins and keeps them (6 per reference: start and end bin per axis) in
// `ref_bins`, for refine() to look up instead of binning every reference again.
// One reference's start and end bins (per axis) counted and kept.
inline void tally(const std::uint32_t (&lo)[4], const std::uint32_t (&hi)[4], std::size_t bins,
                  std::uint32_t* start_counts, std::uint32_t* end_counts,
                  std::uint16_t* ref_bins) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    ++start_counts[axis * bins + lo[axis]];
    ++end_counts[axis * bins + hi[axis]];
    ref_bins[2 * axis] = static_cast<std::uint16_t>(lo[axis]);
    ref_bins[2 * axis + 1] = static_cast<std::uint16_t>(hi[axis]);
  }
}

void count_scalar(const Binner& binner, std::span<const Ref> refs,
                  std::vector<std::uint32_t>& starts, std::vector<std::uint32_t>& ends,
                  std::uint16_t* ref_bins) {
  const auto bins = static_cast<std::size_t>(binner.bins);
  for (const Ref& r : refs) {
    std::uint32_t lo[4] = {}, hi[4] = {};
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = static_cast<std::uint32_t>(binner.bin(axis, r.box.lo[axis]));
      hi[axis] = static_cast<std::uint32_t>(binner.bin(axis, r.box.hi[axis]));
    }
    tally(lo, hi, bins, starts.data(), ends.data(), ref_bins);
    ref_bins += 6;
  }
}

#if COHORT_X86_DISPATCH
// count() with the six bins of a reference computed in two 4-lane vectors, by the same operations
// (subtract, scale, truncate, clamp), so the same bins.
__attribute__((target("sse4.1"))) void count_sse41(const Binner& binner,
                                                   std::span<const Ref> refs,
                                                   std::vector<std::uint32_t>& starts,
                                                   std::vector<std::uint32_t>& ends,
                                                   std::uint16_t* ref_bins) {
  static_assert(sizeof(Bounds) == 6 * sizeof(float) && offsetof(Ref, box) == 0);
  const __m128 lo = _mm_setr_ps(binner.lo.x, binner.lo.y, binner.lo.z, 0.f);
  const __m128 scale = _mm_setr_ps(binner.scale.x, binner.scale.y, binner.scale.z, 0.f);
  const __m128i zero = _mm_setzero_si128(), top = _mm_set1_epi32(binner.bins - 1);
  const auto bins = static_cast<std::size_t>(binner.bins);
  std::uint32_t* const start_counts = starts.data();
  std::uint32_t* const end_counts = ends.data();
  for (const Ref& r : refs) {
    const float* box = &r.box.lo.x;  // lo.xyz, hi.xyz
    // Lane 3 is the next field (hi.x, the triangle index): zeroed, so no denormal enters.
    const __m128 low = _mm_blend_ps(_mm_loadu_ps(box), _mm_setzero_ps(), 8);
    const __m128 high = _mm_blend_ps(_mm_loadu_ps(box + 3), _mm_setzero_ps(), 8);
    const __m128i low_bins = _mm_min_epi32(
        _mm_max_epi32(_mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(low, lo), scale)), zero), top);
    const __m128i high_bins = _mm_min_epi32(
        _mm_max_epi32(_mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(high, lo), scale)), zero), top);
    alignas(16) std::uint32_t l[4], h[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(l), low_bins);
    _mm_store_si128(reinterpret_cast<__m128i*>(h), high_bins);
    tally(l, h, bins, start_counts, end_counts, ref_bins);
    ref_bins += 6;
  }
}
#endif

void count(const Binner& binner, std::span<const Ref> refs, std::vector<std::uint32_t>& starts,
           std::vector<std::uint32_t>& ends, std::uint16_t* ref_bins) {
#if COHORT_X86_DISPATCH
  if (__builtin_cpu_supports("sse4.1")) return count_sse41(binner, refs, starts, ends, ref_bins);
#endif
  count_scalar(binner, refs, starts, ends, ref_bins);
}

void count_all(const Binner& binner, std::span<const Ref> refs, bool parallel,
               PlaneScratch& scratch) {
  std::uint16_t* const ref_bins = scratch.ref_bins.room(6 * refs.size());
  if (!parallel || refs.size() <= 2 * kParallelGrain) {
    scratch.starts.assign(3 * static_cast<std::size_t>(binner.bins), 0u);
    scratch.ends.assign(3 * static_cast<std::size_t>(binner.bins), 0u);
    count(binner, refs, scratch.starts, scratch.ends, ref_bins);
    return;
  }
  BinCounts empty;
  empty.reset(binner.bins);
  BinCounts total = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, refs.size(), kParallelGrain), empty,
      [&](const tbb::blocked_range<std::size_t>& r, BinCounts partial) {
        count(binner, refs.subspan(r.begin(), r.size()), partial.starts, partial.ends,
              ref_bins + 6 * r.begin());
        return partial;
      },
      [](BinCounts a, const BinCounts& b) {
        a.add(b);
        return a;
      });
  scratch.starts = std::move(total.starts);
  scratch.ends = std::move(total.ends);
}

// The best bin boundary of one axis (0: none) with its plane: evaluate_plane over the boundaries
// in ascending order, as evaluate_candidates computes it a vector of boundaries at a time (the
// first of the cheapest, by position). Uses the axis's candidates in `scratch`, which refine()
// fills afresh afterwards.
int best_boundary(const SahContext& c, const Binner& binner, PlaneScratch& scratch, int axis,
                  SplitPlane& axis_best) {
  const int bins = binner.bins;
  const float lo = c.lo[axis], hi = c.hi[axis];
  const float step = c.extent[axis] / static_cast<float>(bins);
  const std::uint32_t* start_counts = scratch.starts.data() + static_cast<std::size_t>(axis * bins);
  const std::uint32_t* end_counts = scratch.ends.data() + static_cast<std::size_t>(axis * bins);
  AxisCandidates& candidates = scratch.candidates[axis];
  candidates.clear();
  candidates.reserve_more(static_cast<std::size_t>(bins));
  std::size_t n = 0;
  std::uint32_t n_left = 0, n_right = c.count;
  for (int b = 1; b < bins; ++b) {
    // Boundary b: references starting in a lower bin reach left of it, those ending in a lower
    // bin do not reach right of it.
    n_left += start_counts[b - 1];
    n_right -= end_counts[b - 1];
    const float pos = lo + step * static_cast<float>(b);
    candidates.pos[n] = pos;
    candidates.left_a[n] = static_cast<float>(n_left);
    candidates.right_a[n] = static_cast<float>(n_right);
    n += pos > lo && pos < hi;  // kept inside the cell only (branch-free)
  }
  candidates.size = n;
  evaluate_candidates(c, axis, candidates, scratch.costs, axis_best);
  if (!axis_best.valid()) return 0;
  // The last boundary at the chosen position (where the step is below the floats' spacing,
  // neighbouring boundaries round to one position).
  for (int b = bins - 1; b >= 1; --b) {
    if (lo + step * static_cast<float>(b) == axis_best.pos) return b;
  }
  return 0;
}

// The bins whose extents get the exact sweep, per axis: up to three disjoint ascending ranges
// [first, last], around the best boundary and at the two ends of the geometry (the first bin where
// a reference starts, the last where one ends), where the planes that cut off empty space lie.
struct Ranges {
  std::array<std::array<int, 2>, 3> range;
  int count = 0;

  void add(int first, int last) {
    for (int k = 0; k < count; ++k) {  // merge with an overlapping or adjacent range
      if (first <= range[k][1] + 1 && last >= range[k][0] - 1) {
        range[k] = {std::min(first, range[k][0]), std::max(last, range[k][1])};
        return;
      }
    }
    range[count++] = {first, last};
  }
  void sort() {
    for (int k = 1; k < count; ++k) {  // at most three: insertion
      for (int j = k; j > 0 && range[j][0] < range[j - 1][0]; --j) std::swap(range[j], range[j - 1]);
    }
    for (int k = 0; k + 1 < count; ++k) {  // a merge above may now touch the next range
      if (range[k + 1][0] <= range[k][1] + 1) {
        range[k][1] = std::max(range[k][1], range[k + 1][1]);
        std::copy(range.begin() + k + 2, range.begin() + count, range.begin() + k + 1);
        --count;
        --k;
      }
    }
  }
};

Ranges exact_ranges(const PlaneScratch& counts, int bins, int axis, int boundary) {
  Ranges r;
  int first = 0, last = bins - 1;
  while (first < last && counts.starts[axis * bins + first] == 0) ++first;
  while (last > first && counts.ends[axis * bins + last] == 0) --last;
  r.add(first, first);
  r.add(last, last);
  if (boundary > 0) r.add(boundary - 1, boundary);
  r.sort();
  return r;
}

// How many of the sorted positions, from `first` on, fall into bins up to `last`.
std::size_t in_bins_up_to(std::span<const float> sorted, std::size_t first, const Binner& binner,
                          int axis, int last) {
  std::size_t end = first;
  while (end < sorted.size() && binner.bin(axis, sorted[end]) <= last) ++end;
  return end - first;
}

#if COHORT_X86_DISPATCH
// Up to this many candidates per axis (four blocks of four vectors, faces set aside) the refined
// bins' candidates are counted directly instead of sorted and swept.
constexpr std::size_t kCountedRefined = 128;

// count_refined on K (1-4) vectors of candidates from `first` on, in registers across the values
// (as count_block in sah_exact.cpp).
template <int K>
__attribute__((target("avx2"))) inline void count_refined_block(const float* pos,
                                                                std::size_t n_starts,
                                                                std::size_t n_ends,
                                                                std::size_t n_flats,
                                                                const std::array<float, 2>& face,
                                                                const std::array<int, 2>& at_face,
                                                                std::size_t first,
                                                                AxisCandidates& x) {
  const auto [p0, p1, p2, p3] = load_vectors<K>(pos + first);
  const __m256i zero = _mm256_setzero_si256();
  __m256i l0 = zero, l1 = zero, l2 = zero, l3 = zero, h0 = zero, h1 = zero, h2 = zero, h3 = zero;
  const float* starts = pos;
  const float* ends = pos + n_starts;
  const float* flats = ends + n_ends;
  count_values<K, _CMP_LT_OQ>(starts, n_starts, p0, p1, p2, p3, l0, l1, l2, l3);
  count_values<K, _CMP_LT_OQ>(flats, n_flats, p0, p1, p2, p3, l0, l1, l2, l3);
  count_values<K, _CMP_LE_OQ>(ends, n_ends, p0, p1, p2, p3, h0, h1, h2, h3);
  count_values<K, _CMP_LE_OQ>(flats, n_flats, p0, p1, p2, p3, h0, h1, h2, h3);
  __m256i e0 = zero, e1 = zero, e2 = zero, e3 = zero;
  count_values<K, _CMP_EQ_OQ>(flats, n_flats, p0, p1, p2, p3, e0, e1, e2, e3);
  const __m256 ps[4] = {p0, p1, p2, p3};
  const __m256i ls[4] = {l0, l1, l2, l3}, hs[4] = {h0, h1, h2, h3}, es[4] = {e0, e1, e2, e3};
  const __m256 lo = _mm256_set1_ps(face[0]), hi = _mm256_set1_ps(face[1]);
  const __m256i at_lo = _mm256_set1_epi32(at_face[0]), at_hi = _mm256_set1_epi32(at_face[1]);
  for (int k = 0; k < K; ++k) {
    // The starts on the cell's low face lie left of every candidate above it; the ends on its
    // high face at or left of the candidate there only.
    const __m256i l = _mm256_add_epi32(
        ls[k], _mm256_and_si256(at_lo, _mm256_castps_si256(_mm256_cmp_ps(lo, ps[k], _CMP_LT_OQ))));
    const __m256i h = _mm256_add_epi32(
        hs[k], _mm256_and_si256(at_hi, _mm256_castps_si256(_mm256_cmp_ps(hi, ps[k], _CMP_LE_OQ))));
    const std::size_t i = first + 8 * static_cast<std::size_t>(k);
    const __m256 left_b = _mm256_add_ps(_mm256_loadu_ps(x.left_b.data() + i), _mm256_cvtepi32_ps(l));
    const __m256 right_a = _mm256_sub_ps(_mm256_loadu_ps(x.right_a.data() + i), _mm256_cvtepi32_ps(h));
    const __m256 planar = _mm256_cvtepi32_ps(es[k]);
    _mm256_storeu_ps(x.left_b.data() + i, left_b);
    _mm256_storeu_ps(x.left_a.data() + i, _mm256_add_ps(left_b, planar));
    _mm256_storeu_ps(x.right_a.data() + i, right_a);
    _mm256_storeu_ps(x.right_b.data() + i, _mm256_add_ps(right_a, planar));
  }
}

// The counts merge_candidates gives the candidates x.pos[0, x.size): the non-face starts (the
// first n_starts), the non-face ends (next n_ends), the flat positions (next n_flats), then the
// faces. x.left_b and x.right_a come in holding each candidate's counts from the bins outside the
// refined ones below it: references starting there, and those not ending there. Counted against
// every refined value, as a candidate's counts are those of all values before it.
__attribute__((target("avx2"))) void count_refined(std::size_t n_starts, std::size_t n_ends,
                                                   std::size_t n_flats,
                                                   const std::array<float, 2>& face,
                                                   const std::array<int, 2>& at_face,
                                                   AxisCandidates& x) {
  const float* pos = x.pos.data();
  const std::size_t m = whole_lanes(x.size);
  std::size_t first = 0;
  for (; first + 4 * kCandidateLanes <= m; first += 4 * kCandidateLanes) {
    count_refined_block<4>(pos, n_starts, n_ends, n_flats, face, at_face, first, x);
  }
  switch ((m - first) / kCandidateLanes) {
    case 3: count_refined_block<3>(pos, n_starts, n_ends, n_flats, face, at_face, first, x); break;
    case 2: count_refined_block<2>(pos, n_starts, n_ends, n_flats, face, at_face, first, x); break;
    case 1: count_refined_block<1>(pos, n_starts, n_ends, n_flats, face, at_face, first, x); break;
    default: break;
  }
}
#endif

// The candidates of one axis's refined bins with their counts, counted directly instead of sorted
// and swept where there are few of them (most binned nodes below a few hundred references): the
// same candidates with the same counts, so evaluate_candidates chooses the same plane. A start
// on the cell's low face or an end on its high face (often half of the values: references
// clipped by an ancestor's plane) is counted once per face instead of once per candidate. False
// where this does not apply (too many candidates, or no AVX2); then `out` is left empty.
bool count_refined_axis(const SahContext& c, const Binner& binner, int axis,
                        const std::array<Ranges, 3>& ranges, const PlaneScratch& scratch,
                        AxisCandidates& out) {
#if COHORT_X86_DISPATCH
  const AxisExtents& x = scratch.extents[axis];
  const std::size_t values = x.starts.size() + x.ends.size() + x.flats.size();
  if (scratch.sweep_refined || !__builtin_cpu_supports("avx2")) return false;
  const std::array<float, 2> face{c.lo[axis] + 0.f, c.hi[axis] + 0.f};
  out.clear();
  out.reserve_more(values + 2);
  float* pos = out.pos.data();
  std::size_t m = 0;
  std::array<int, 2> at_face{0, 0};
  for (const float v : x.starts) {
    pos[m] = v;  // kept unless on the low face (branch-free)
    const bool on_face = v == face[0];
    at_face[0] += on_face;
    m += !on_face;
  }
  const std::size_t n_starts = m;
  for (const float v : x.ends) {
    pos[m] = v;
    const bool on_face = v == face[1];
    at_face[1] += on_face;
    m += !on_face;
  }
  const std::size_t n_ends = m - n_starts;
  for (const float v : x.flats) pos[m++] = v;
  if (at_face[0] > 0) pos[m++] = face[0];
  if (at_face[1] > 0) pos[m++] = face[1];
  if (m > kCountedRefined) {
    out.clear();
    return false;
  }
  out.size = m;
  out.planar = !x.flats.empty();
  // Per range, the counts of the bins below it that are not refined (the refined ones below it
  // are counted value by value).
  const auto bins = static_cast<std::size_t>(binner.bins);
  const std::uint8_t* refined = scratch.refined.data() + static_cast<std::size_t>(axis) * bins;
  const std::uint32_t* start_counts = scratch.starts.data() + static_cast<std::size_t>(axis) * bins;
  const std::uint32_t* end_counts = scratch.ends.data() + static_cast<std::size_t>(axis) * bins;
  const Ranges& r = ranges[axis];
  std::array<float, 3> base_left{}, base_right{};
  std::uint32_t n_left = 0, n_right = c.count;
  std::size_t counted = 0;
  for (int k = 0; k < r.count; ++k) {
    for (; counted < static_cast<std::size_t>(r.range[k][0]); ++counted) {
      if (refined[counted]) continue;
      n_left += start_counts[counted];
      n_right -= end_counts[counted];
    }
    base_left[k] = static_cast<float>(n_left);
    base_right[k] = static_cast<float>(n_right);
  }
  for (std::size_t i = 0; i < m; ++i) {
    const int bin = binner.bin(axis, pos[i]);
    int k = 0;
    while (k + 1 < r.count && r.range[k + 1][0] <= bin) ++k;
    out.left_b[i] = base_left[k];
    out.right_a[i] = base_right[k];
  }
  count_refined(n_starts, n_ends, x.flats.size(), face, at_face, out);
  return true;
#else
  (void)c, (void)binner, (void)axis, (void)ranges, (void)scratch, (void)out;
  return false;
#endif
}

// Exact counts inside a range of bins: every reference starting in a lower bin lies left of each
// position there, every one ending in a lower bin right of none (the bin index is monotone in the
// position), so a Wald & Havran sweep over the extents of the range, started from the prefix
// counts, evaluates each of them exactly. This recovers the planes at triangle boundaries, which
// a KD-tree's cost depends on (cutting off empty space tightly) and bin boundaries miss.
void refine(const SahContext& c, const Binner& binner, std::span<const Ref> refs,
            const std::array<Ranges, 3>& ranges, bool parallel, PlaneScratch& scratch,
            SplitPlane& best) {
  for (AxisExtents& x : scratch.extents) x.clear();
  // A lookup per position instead of a search through the ranges.
  const auto bins = static_cast<std::size_t>(binner.bins);
  scratch.refined.assign(3 * bins, 0);
  for (int axis = 0; axis < 3; ++axis) {
    for (int k = 0; k < ranges[axis].count; ++k) {
      for (int b = ranges[axis].range[k][0]; b <= ranges[axis].range[k][1]; ++b) {
        scratch.refined[axis * bins + static_cast<std::size_t>(b)] = 1;
      }
    }
  }
  // The bins count_all() kept (binning -0 and +0 alike). Every position is written to `buffer`
  // (9 per reference) and the kept ones counted, so whether a position is in a refined bin is no
  // branch to mispredict; the kept ones are then appended to `extents`.
  auto gather = [&](std::size_t first, std::size_t last, float* buffer, NodeExtents& extents) {
    const std::size_t n = last - first;
    std::array<float*, 3> starts, ends, flats;
    std::array<std::size_t, 3> n_starts{}, n_ends{}, n_flats{};
    for (int axis = 0; axis < 3; ++axis) {
      starts[axis] = buffer + (3 * axis) * n;
      ends[axis] = buffer + (3 * axis + 1) * n;
      flats[axis] = buffer + (3 * axis + 2) * n;
    }
    for (std::size_t i = first; i < last; ++i) {
      const Ref& r = refs[i];
      const std::uint16_t* ref_bins = scratch.ref_bins.data() + 6 * i;
      // Most references have no end in a refined bin (in the largest nodes about 2 in 100 ends
      // are kept): one well-predicted branch skips them.
      const std::uint8_t* refined_bins = scratch.refined.data();
      if ((refined_bins[ref_bins[0]] | refined_bins[ref_bins[1]] | refined_bins[bins + ref_bins[2]] |
           refined_bins[bins + ref_bins[3]] | refined_bins[2 * bins + ref_bins[4]] |
           refined_bins[2 * bins + ref_bins[5]]) == 0) {
        continue;
      }
      for (int axis = 0; axis < 3; ++axis) {
        const std::uint8_t* refined = scratch.refined.data() + axis * bins;
        const float lo = r.box.lo[axis] + 0.f, hi = r.box.hi[axis] + 0.f;
        const std::size_t flat = lo == hi;
        const std::size_t lo_refined = refined[ref_bins[2 * axis]];
        const std::size_t hi_refined = refined[ref_bins[2 * axis + 1]];
        starts[axis][n_starts[axis]] = lo;
        n_starts[axis] += lo_refined & (flat ^ 1);
        ends[axis][n_ends[axis]] = hi;
        n_ends[axis] += hi_refined & (flat ^ 1);
        flats[axis][n_flats[axis]] = lo;
        n_flats[axis] += lo_refined & flat;
      }
    }
    for (int axis = 0; axis < 3; ++axis) {
      AxisExtents& x = extents[axis];
      x.starts.insert(x.starts.end(), starts[axis], starts[axis] + n_starts[axis]);
      x.ends.insert(x.ends.end(), ends[axis], ends[axis] + n_ends[axis]);
      x.flats.insert(x.flats.end(), flats[axis], flats[axis] + n_flats[axis]);
    }
  };
  if (!parallel || refs.size() <= 2 * kParallelGrain) {
    gather(0, refs.size(), scratch.gathered.room(9 * refs.size()), scratch.extents);
  } else {
    // Chunks gathered in parallel and joined; the order does not matter, the lists are sorted.
    const std::size_t chunks = (refs.size() + kParallelGrain - 1) / kParallelGrain;
    std::vector<NodeExtents> parts(chunks);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
      const std::size_t first = k * kParallelGrain;
      const auto buffer = std::make_unique_for_overwrite<float[]>(9 * kParallelGrain);
      gather(first, std::min(refs.size(), first + kParallelGrain), buffer.get(), parts[k]);
    });
    for (const NodeExtents& part : parts) {
      for (int axis = 0; axis < 3; ++axis) {
        AxisExtents& x = scratch.extents[axis];
        const AxisExtents& y = part[axis];
        x.starts.insert(x.starts.end(), y.starts.begin(), y.starts.end());
        x.ends.insert(x.ends.end(), y.ends.begin(), y.ends.end());
        x.flats.insert(x.flats.end(), y.flats.begin(), y.flats.end());
      }
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    AxisCandidates& candidates = scratch.candidates[axis];
    if (count_refined_axis(c, binner, axis, ranges, scratch, candidates)) {
      evaluate_candidates(c, axis, candidates, scratch.costs, best);
      continue;
    }
    AxisExtents& x = scratch.extents[axis];
    x.sort(c.lo[axis], c.hi[axis]);
    // The sorted positions fall into the ranges in order; each range's sweep starts from the
    // counts of the bins below it.
    candidates.clear();
    std::size_t s = 0, e = 0, f = 0;
    std::uint32_t n_left = 0, n_right = c.count;
    int counted = 0;  // bins [0, counted) are in n_left / n_right
    for (int k = 0; k < ranges[axis].count; ++k) {
      const auto [first, last] = ranges[axis].range[k];
      for (; counted < first; ++counted) {
        n_left += scratch.starts[axis * binner.bins + counted];
        n_right -= scratch.ends[axis * binner.bins + counted];
      }
      const std::size_t ns = in_bins_up_to(x.starts, s, binner, axis, last);
      const std::size_t ne = in_bins_up_to(x.ends, e, binner, axis, last);
      const std::size_t nf = in_bins_up_to(x.flats, f, binner, axis, last);
      merge_candidates(std::span<const float>(x.starts).subspan(s, ns),
                       std::span<const float>(x.ends).subspan(e, ne),
                       std::span<const float>(x.flats).subspan(f, nf), n_left, n_right,
                       candidates);
      s += ns;
      e += ne;
      f += nf;
    }
    evaluate_candidates(c, axis, candidates, scratch.costs, best);
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
    keep_better(best, axis_best);
  }
  std::array<Ranges, 3> ranges{};
  for (int axis = 0; axis < 3; ++axis) {
    if (c.extent[axis] > 0.f) ranges[axis] = exact_ranges(scratch, bins, axis, boundary[axis]);
  }
  refine(c, binner, refs, ranges, parallel, scratch, best);
  return best;
}

}  // namespace cohort::kd
