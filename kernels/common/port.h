/* Portability layer: lets the plain-C device headers compile as OpenCL C 1.2 and as host C++
 * (and later CUDA C++). Only what the shared headers need lives here. */
#ifndef COHORT_PORT_H
#define COHORT_PORT_H

#ifdef __OPENCL_VERSION__
/* No a*b+c -> fma contraction: the host build does not contract either, so host and device
 * traversal agree bit for bit, and every kernel rounds the shared code the same way. */
#pragma OPENCL FP_CONTRACT OFF
typedef uint uint32_t;
typedef int int32_t;
typedef ulong uint64_t;
#define CO_GLOBAL __global
#define CO_CONSTANT __constant
#define CO_LOCAL __local
#define CO_INLINE inline
#define CO_ALIGN(n) __attribute__((aligned(n)))
#define CO_STATIC_ASSERT(cond, msg)
typedef float4 co_float4;
#define co_as_float(u) as_float(u)
#define co_as_uint(f) as_uint(f)
#else
#include <cmath>
#include <cstdint>
#include <cstring>
using std::acos;
using std::atan2;
using std::fabs;
using std::floor;
using std::fmax;
using std::fmin;
using std::sqrt;
#define CO_GLOBAL
#define CO_CONSTANT
#define CO_LOCAL
#define CO_INLINE inline
#define CO_ALIGN(n) alignas(n)
#define CO_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
/* Same size and alignment as OpenCL's float4 (cl_float4). */
typedef struct CO_ALIGN(16) co_float4 {
  float x, y, z, w;
} co_float4;
inline float co_as_float(uint32_t u) { float f; std::memcpy(&f, &u, 4); return f; }
inline uint32_t co_as_uint(float f) { uint32_t u; std::memcpy(&u, &f, 4); return u; }
#endif

#endif
