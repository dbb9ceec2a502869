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
#else
#define COHORT_X86_DISPATCH 0
#define COHORT_AVX2_CLONES
#endif
