// Whether this build compiles code for newer x86 vector extensions beside the baseline and picks
// one at run time (GCC's target attributes and __builtin_cpu_supports). Elsewhere, and with other
// compilers, the portable code is all there is. Every dispatched version computes the same bits
// as the portable one: AVX2 alone does not enable fused multiply-add.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define COHORT_X86_DISPATCH 1
#include <immintrin.h>

#include <cstddef>
// A function compiled twice, for AVX2 and for the baseline, chosen when the program loads.
#define COHORT_AVX2_CLONES __attribute__((target_clones("avx2", "default")))

// Adds one per lane where `value Predicate p` holds to an integer count: a comparison's lanes are
// all ones (-1 as an integer) where it holds, so subtracting them counts (two operations, no float
// addition's latency). Counts are kept in named variables, not arrays: GCC kept arrays of vectors
// in memory across a loop and stored every count on every iteration.
template <int Predicate>
__attribute__((target("avx2"))) inline void count_if(__m256i& count, __m256 value, __m256 p) {
  count = _mm256_sub_epi32(count, _mm256_castps_si256(_mm256_cmp_ps(value, p, Predicate)));
}

// Four vectors of 8 floats, of which the first K (1-4) were loaded from `at`; the others repeat
// the first (loaded in bounds, never used).
struct Vectors4 {
  __m256 v0, v1, v2, v3;
};
template <int K>
__attribute__((target("avx2"))) inline Vectors4 load_vectors(const float* at) {
  static_assert(K >= 1 && K <= 4);
  return {_mm256_loadu_ps(at), _mm256_loadu_ps(at + 8 * (K > 1)), _mm256_loadu_ps(at + 16 * (K > 2)),
          _mm256_loadu_ps(at + 24 * (K > 3))};
}

// Adds to c0-c3 (the first K used), per lane of p0-p3, how many of the values v have
// `v Predicate p` (count_if).
template <int K, int Predicate>
__attribute__((target("avx2"))) inline void count_values(const float* values, std::size_t n,
                                                         __m256 p0, __m256 p1, __m256 p2,
                                                         __m256 p3, __m256i& c0, __m256i& c1,
                                                         __m256i& c2, __m256i& c3) {
  for (std::size_t j = 0; j < n; ++j) {
    const __m256 v = _mm256_broadcast_ss(values + j);
    count_if<Predicate>(c0, v, p0);
    if constexpr (K > 1) count_if<Predicate>(c1, v, p1);
    if constexpr (K > 2) count_if<Predicate>(c2, v, p2);
    if constexpr (K > 3) count_if<Predicate>(c3, v, p3);
  }
}
#else
#define COHORT_X86_DISPATCH 0
#define COHORT_AVX2_CLONES
#endif
