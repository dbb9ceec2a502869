// Whether this build compiles code for newer x86 vector extensions beside the baseline and picks
// one at run time (GCC's target attributes and __builtin_cpu_supports). Elsewhere, and with other
// compilers, the portable code is all there is. Every dispatched version computes the same bits
// as the portable one: AVX2 alone does not enable fused multiply-add.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define COHORT_X86_DISPATCH 1
#include <immintrin.h>
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
#else
#define COHORT_X86_DISPATCH 0
#define COHORT_AVX2_CLONES
#endif
