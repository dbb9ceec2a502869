/* Portability layer: lets the plain-C device headers compile as OpenCL C 1.2, as CUDA C++ (nvcc and
 * NVRTC) and as host C++. Only what the shared headers need lives here.
 *
 * Kernels are written once, in the *_kernels.h headers next to this one, with these macros; the
 * .cl files under kernels/ and the .cu files under kernels/cuda/ only include them:
 *   CO_KERNEL / CO_KERNEL_WG(n)  a kernel entry point (with a required work-group size)
 *   CO_LOCAL_PARAM(T, name)      a kernel's one dynamically sized local (shared) array: an argument in
 *                                OpenCL and on the host, the launch's dynamic shared memory in CUDA;
 *                                CO_LOCAL_BIND(T, name) at the top of the body makes it visible
 *   CO_SHARED                    a fixed-size local array declared in a kernel body
 *   co_global_id() ...           work-item indices in dimension 0; co_barrier(): a work-group barrier
 *   co_atomic_add / co_atomic_inc / co_atomic_max / co_atomic_xchg on 32-bit global or local words
 *   (return the old value); co_atomic_load reads one through the atomic path (a spin-wait's read)
 * Rounding: OpenCL is built without contraction (the pragma below) and, where the device offers
 * it, with correctly rounded division and sqrt; CUDA with -fmad=false -prec-div=true
 * -prec-sqrt=true; the host never contracts. Then +, -, *, / and sqrt round identically on every
 * side, and the shared code uses nothing else (see microfacet.h for sin and cos). The one explicit
 * fma, co_f4_fma / co_f8_fma (correctly rounded everywhere: OpenCL's fma, CUDA's and the host's
 * fmaf), is in the BVH box tests, which decide which nodes a walk visits, never its hit
 * (bvh4_traverse.h, BVH_SLAB4). */
#ifndef COHORT_PORT_H
#define COHORT_PORT_H

#if defined(__OPENCL_VERSION__)
/* No a*b+c -> fma contraction: the host build does not contract either, so host and device
 * traversal agree bit for bit, and every kernel rounds the shared code the same way. */
#pragma OPENCL FP_CONTRACT OFF
typedef uint uint32_t;
typedef int int32_t;
typedef ulong uint64_t;
#define CO_GLOBAL __global
#define CO_CONSTANT __constant
#define CO_CONSTANT_DATA __constant
#define CO_LOCAL __local
#define CO_SHARED __local
#define CO_INLINE inline
/* CO_FORCE_INLINE: for a hot helper the compiler would otherwise keep as a call (PoCL's Clang kept
 * bvh4_descend one, with the walk's state passed through memory) */
#if defined(__clang__)
#define CO_FORCE_INLINE inline __attribute__((always_inline))
#else
#define CO_FORCE_INLINE inline
#endif
#define CO_ALIGN(n) __attribute__((aligned(n)))
#define CO_STATIC_ASSERT(cond, msg)
#define CO_KERNEL __kernel void
#define CO_KERNEL_WG(n) __kernel __attribute__((reqd_work_group_size(n, 1, 1))) void
#define CO_LOCAL_PARAM(T, name) __local T* name,
#define CO_LOCAL_BIND(T, name)
typedef float4 co_float4;
typedef uint4 co_uint4;
#define co_make_float4(x, y, z, w) ((float4)((x), (y), (z), (w)))
#define co_make_uint4(x, y, z, w) ((uint4)((x), (y), (z), (w)))
#define co_as_float(u) as_float(u)
#define co_as_uint(f) as_uint(f)
#define co_global_id() ((uint32_t)get_global_id(0))
#define co_local_id() ((uint32_t)get_local_id(0))
#define co_local_size() ((uint32_t)get_local_size(0))
#define co_group_id() ((uint32_t)get_group_id(0))
#define co_barrier() barrier(CLK_LOCAL_MEM_FENCE)
#define co_atomic_add(p, v) atomic_add((p), (v))
#define co_atomic_inc(p) atomic_inc(p)
#define co_atomic_max(p, v) atomic_max((p), (v))
#define co_atomic_xchg(p, v) atomic_xchg((p), (v))
#define co_atomic_load(p) atomic_or((p), 0u)

#elif defined(__CUDACC__)
#if defined(__CUDACC_RTC__)
/* NVRTC has no standard headers; these are glibc's LP64 types, so nvcc and NVRTC agree. */
typedef unsigned int uint32_t;
typedef int int32_t;
typedef unsigned long uint64_t;
#else
#include <cstdint>
#endif
#ifndef INFINITY
#define INFINITY __int_as_float(0x7f800000)
#endif
#define CO_GLOBAL
#define CO_CONSTANT
#define CO_CONSTANT_DATA static __constant__ const
#define CO_LOCAL
#define CO_SHARED __shared__
#define CO_INLINE __device__ inline
#define CO_FORCE_INLINE __device__ __forceinline__
#define CO_ALIGN(n) __align__(n)
#define CO_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
#define CO_KERNEL extern "C" __global__ void
#define CO_KERNEL_WG(n) extern "C" __global__ void __launch_bounds__(n)
#define CO_LOCAL_PARAM(T, name)
#define CO_LOCAL_BIND(T, name)                             \
  extern __shared__ __align__(16) unsigned char co_dynamic_shared[]; \
  T* name = (T*)co_dynamic_shared;
typedef float4 co_float4; /* 16 bytes, 16-aligned: cl_float4's layout */
typedef uint4 co_uint4;
#define co_make_float4(x, y, z, w) make_float4((x), (y), (z), (w))
#define co_make_uint4(x, y, z, w) make_uint4((x), (y), (z), (w))
#define co_as_float(u) __uint_as_float(u)
#define co_as_uint(f) __float_as_uint(f)
#define co_global_id() (blockIdx.x * blockDim.x + threadIdx.x)
#define co_local_id() (threadIdx.x)
#define co_local_size() (blockDim.x)
#define co_group_id() (blockIdx.x)
#define co_barrier() __syncthreads()
#define co_atomic_add(p, v) atomicAdd((p), (v))
#define co_atomic_inc(p) atomicAdd((p), 1u)
#define co_atomic_max(p, v) atomicMax((p), (v))
#define co_atomic_xchg(p, v) atomicExch((p), (v))
#define co_atomic_load(p) atomicOr((p), 0u)

#else
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
using std::acos;
using std::atan2;
using std::fabs;
using std::floor;
using std::fmax;
using std::fmaf;
using std::fmin;
using std::sqrt;
#define CO_GLOBAL
#define CO_CONSTANT
#define CO_CONSTANT_DATA static const
#define CO_LOCAL
#define CO_SHARED
#define CO_INLINE inline
#define CO_FORCE_INLINE inline
#define CO_ALIGN(n) alignas(n)
#define CO_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
/* Same size and alignment as OpenCL's float4 (cl_float4). */
typedef struct CO_ALIGN(16) co_float4 {
  float x, y, z, w;
} co_float4;
typedef struct CO_ALIGN(16) co_uint4 {
  uint32_t x, y, z, w;
} co_uint4;
inline co_float4 co_make_float4(float x, float y, float z, float w) { return co_float4{x, y, z, w}; }
inline co_uint4 co_make_uint4(uint32_t x, uint32_t y, uint32_t z, uint32_t w) { return co_uint4{x, y, z, w}; }
inline float co_as_float(uint32_t u) { float f; std::memcpy(&f, &u, 4); return f; }
inline uint32_t co_as_uint(float f) { uint32_t u; std::memcpy(&u, &f, 4); return u; }

/* Kernels run on the host (tests of the shared kernel code) one work item at a time, in work-group
 * order; the runner sets the indices here. Barriers are no-ops, so only kernels whose work-groups
 * have one work item, or that never share local memory, run correctly this way. */
struct CoHostWorkItem {
  uint32_t global_id, local_id, local_size, group_id;
};
inline thread_local CoHostWorkItem co_host_item{};
#define CO_KERNEL inline void
#define CO_KERNEL_WG(n) inline void
#define CO_LOCAL_PARAM(T, name) T* name,
#define CO_LOCAL_BIND(T, name)
#define co_global_id() (co_host_item.global_id)
#define co_local_id() (co_host_item.local_id)
#define co_local_size() (co_host_item.local_size)
#define co_group_id() (co_host_item.group_id)
#define co_barrier() ((void)0)
inline uint32_t co_atomic_add(uint32_t* p, uint32_t v) { uint32_t old = *p; *p = old + v; return old; }
inline uint32_t co_atomic_inc(uint32_t* p) { return co_atomic_add(p, 1u); }
inline uint32_t co_atomic_max(uint32_t* p, uint32_t v) { uint32_t old = *p; *p = old > v ? old : v; return old; }
inline uint32_t co_atomic_xchg(uint32_t* p, uint32_t v) { uint32_t old = *p; *p = v; return old; }
inline uint32_t co_atomic_load(const uint32_t* p) { return *p; }
#endif

/* Four-lane float arithmetic for the 4-wide BVH's box tests and the four-triangle test: OpenCL's
 * float4 operators (one SIMD instruction each on a CPU), lane by lane elsewhere. co_f4_less gives a
 * 4-bit mask, lane x in bit 0; co_f4_store writes the four lanes to p[0-3].
 * min and max (only the box tests take them, and no NaN reaches them there) are a compare and a
 * select, or with CO_MINMAX_INSTRUCTIONS fmin and fmax, one instruction each on a GPU where the
 * compare and select take two: the same values. A program opts in (COHORT_PROGRAM_MINMAX, before
 * its first include: naive and trace) and the device must be a GPU (every CUDA device; the host's
 * -DCOHORT_GPU_MINMAX for OpenCL GPUs and for Oclgrind, so that CI's checks run it). On an H100 they
 * traced primary rays 1.09-1.14x faster (2026-12-07), but the wavefront extension kernel, which the
 * default sc+rg spends most of its time in, and the pth program (hash and pth 0.96x) ran slower with
 * them (docs/design.md, "Box tests"). */
#if defined(COHORT_PROGRAM_MINMAX) && (defined(COHORT_GPU_MINMAX) || defined(__CUDACC__))
#define CO_MINMAX_INSTRUCTIONS 1
#endif
/* A pass's work items take its pixels in 8x4 tiles (tiled_pixel, types.h) on GPUs: every CUDA
 * device, and the host's -DCOHORT_PIXEL_TILES for OpenCL GPUs and for Oclgrind (so that CI renders
 * through it to PoCL's bits). CPUs keep rows: PoCL measured no gain from the tiles (docs/design.md,
 * "Pixel order"). */
#if defined(COHORT_PIXEL_TILES) || defined(__CUDACC__)
#define CO_PIXEL_TILES 1
#endif
#if defined(__OPENCL_VERSION__)
#define co_f4_splat(s) ((float4)(s))
#define co_f4_add(a, b) ((a) + (b))
#define co_f4_sub(a, b) ((a) - (b))
#define co_f4_mul(a, b) ((a) * (b))
#define co_f4_scale(a, s) ((a) * (s))
#define co_f4_fma(a, b, c) fma((a), (b), (c))
#if defined(CO_MINMAX_INSTRUCTIONS)
#define co_f4_min(a, b) fmin((a), (b))
#define co_f4_max(a, b) fmax((a), (b))
#else
#define co_f4_min(a, b) select((b), (a), (a) < (b))
#define co_f4_max(a, b) select((b), (a), (a) > (b))
#endif
#define co_f4_div(a, b) ((a) / (b))
#define co_f4_store(v, p) vstore4((v), 0, (p))
CO_INLINE uint32_t co_f4_less(float4 a, float4 b) {
  int4 m = a < b;
#if defined(__clang__) && defined(__SSE__) && defined(__has_builtin)
#if __has_builtin(__builtin_ia32_movmskps)
  /* as co_f8_less: one movmskps of the lanes' sign bits where Clang compiles for an x86 host */
  return (uint32_t)__builtin_ia32_movmskps(as_float4(m));
#endif
#endif
  return (uint32_t)((m.x & 1) | (m.y & 2) | (m.z & 4) | (m.w & 8));
}
#else
CO_INLINE co_float4 co_f4_splat(float s) { return co_make_float4(s, s, s, s); }
CO_INLINE co_float4 co_f4_add(co_float4 a, co_float4 b) { return co_make_float4(a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w); }
CO_INLINE co_float4 co_f4_sub(co_float4 a, co_float4 b) { return co_make_float4(a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w); }
CO_INLINE co_float4 co_f4_mul(co_float4 a, co_float4 b) { return co_make_float4(a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w); }
CO_INLINE co_float4 co_f4_scale(co_float4 a, float s) { return co_make_float4(a.x * s, a.y * s, a.z * s, a.w * s); }
CO_INLINE co_float4 co_f4_fma(co_float4 a, co_float4 b, co_float4 c) {
  return co_make_float4(fmaf(a.x, b.x, c.x), fmaf(a.y, b.y, c.y), fmaf(a.z, b.z, c.z), fmaf(a.w, b.w, c.w));
}
#if defined(CO_MINMAX_INSTRUCTIONS)
CO_INLINE float co_f_min(float a, float b) { return fminf(a, b); }
CO_INLINE float co_f_max(float a, float b) { return fmaxf(a, b); }
#else
CO_INLINE float co_f_min(float a, float b) { return a < b ? a : b; }
CO_INLINE float co_f_max(float a, float b) { return a > b ? a : b; }
#endif
CO_INLINE co_float4 co_f4_min(co_float4 a, co_float4 b) {
  return co_make_float4(co_f_min(a.x, b.x), co_f_min(a.y, b.y), co_f_min(a.z, b.z), co_f_min(a.w, b.w));
}
CO_INLINE co_float4 co_f4_max(co_float4 a, co_float4 b) {
  return co_make_float4(co_f_max(a.x, b.x), co_f_max(a.y, b.y), co_f_max(a.z, b.z), co_f_max(a.w, b.w));
}
CO_INLINE co_float4 co_f4_div(co_float4 a, co_float4 b) { return co_make_float4(a.x / b.x, a.y / b.y, a.z / b.z, a.w / b.w); }
CO_INLINE void co_f4_store(co_float4 v, float* p) { p[0] = v.x; p[1] = v.y; p[2] = v.z; p[3] = v.w; }
CO_INLINE uint32_t co_f4_less(co_float4 a, co_float4 b) {
  return (a.x < b.x ? 1u : 0u) | (a.y < b.y ? 2u : 0u) | (a.z < b.z ? 4u : 0u) | (a.w < b.w ? 8u : 0u);
}
#endif

/* Eight-lane float arithmetic for the 8-wide BVH with float planes (--tree bvh8f): OpenCL's float8
 * (one AVX instruction each where the CPU has it, two SSE ones where not), lane by lane elsewhere
 * (the CUDA and host fallback, as the four-lane helpers'). co_f8_load and co_f8_store move eight
 * consecutive floats (no alignment assumed); co_f8_less gives an 8-bit mask, lane 0 in bit 0. */
#if defined(__OPENCL_VERSION__)
typedef float8 co_float8;
#define co_f8_load(p) vload8(0, (p))
#define co_f8_store(v, p) vstore8((v), 0, (p))
#define co_f8_splat(s) ((float8)(s))
#define co_f8_sub(a, b) ((a) - (b))
#define co_f8_mul(a, b) ((a) * (b))
#define co_f8_scale(a, s) ((a) * (s))
#define co_f8_fma(a, b, c) fma((a), (b), (c))
#define co_f8_min(a, b) select((b), (a), (a) < (b))
#define co_f8_max(a, b) select((b), (a), (a) > (b))
CO_INLINE uint32_t co_f8_less(float8 a, float8 b) {
  int8 m = a < b;
#if defined(__clang__) && defined(__AVX__) && defined(__has_builtin)
#if __has_builtin(__builtin_ia32_movmskps256)
  /* an x86 CPU runtime that compiles with Clang for the host (PoCL): one vmovmskps of the lanes'
   * sign bits in place of the ten instructions the portable form below becomes there */
  return (uint32_t)__builtin_ia32_movmskps256(as_float8(m));
#endif
#endif
  return (uint32_t)((m.s0 & 1) | (m.s1 & 2) | (m.s2 & 4) | (m.s3 & 8) | (m.s4 & 16) | (m.s5 & 32) | (m.s6 & 64) |
                    (m.s7 & 128));
}
#else
typedef struct co_float8 {
  float s[8];
} co_float8;
CO_INLINE co_float8 co_f8_load(const CO_GLOBAL float* p) {
  co_float8 r;
  for (int i = 0; i < 8; ++i) r.s[i] = p[i];
  return r;
}
CO_INLINE void co_f8_store(co_float8 v, float* p) {
  for (int i = 0; i < 8; ++i) p[i] = v.s[i];
}
CO_INLINE co_float8 co_f8_splat(float s) {
  co_float8 r;
  for (int i = 0; i < 8; ++i) r.s[i] = s;
  return r;
}
CO_INLINE co_float8 co_f8_sub(co_float8 a, co_float8 b) {
  for (int i = 0; i < 8; ++i) a.s[i] = a.s[i] - b.s[i];
  return a;
}
CO_INLINE co_float8 co_f8_mul(co_float8 a, co_float8 b) {
  for (int i = 0; i < 8; ++i) a.s[i] = a.s[i] * b.s[i];
  return a;
}
CO_INLINE co_float8 co_f8_scale(co_float8 a, float s) {
  for (int i = 0; i < 8; ++i) a.s[i] = a.s[i] * s;
  return a;
}
CO_INLINE co_float8 co_f8_fma(co_float8 a, co_float8 b, co_float8 c) {
  for (int i = 0; i < 8; ++i) a.s[i] = fmaf(a.s[i], b.s[i], c.s[i]);
  return a;
}
CO_INLINE co_float8 co_f8_min(co_float8 a, co_float8 b) {
  for (int i = 0; i < 8; ++i) a.s[i] = a.s[i] < b.s[i] ? a.s[i] : b.s[i];
  return a;
}
CO_INLINE co_float8 co_f8_max(co_float8 a, co_float8 b) {
  for (int i = 0; i < 8; ++i) a.s[i] = a.s[i] > b.s[i] ? a.s[i] : b.s[i];
  return a;
}
CO_INLINE uint32_t co_f8_less(co_float8 a, co_float8 b) {
  uint32_t m = 0u;
  for (int i = 0; i < 8; ++i) m |= a.s[i] < b.s[i] ? 1u << i : 0u;
  return m;
}
#endif

/* Eight counters, one a lane (bvh8f_trace_packet's visits per ray): co_c8_count adds 1 to the lanes
 * of `mask`'s bits (lane 0 in bit 0). OpenCL's int8, a few vector operations where eight scalar
 * increments of a memory array form a chain of dependent stores; lane by lane elsewhere. */
#if defined(__OPENCL_VERSION__)
typedef int8 co_count8;
#define co_c8_zero() ((int8)(0))
/* a true vector comparison is -1 in each lane */
#define co_c8_count(c, mask) \
  ((c) - ((((int8)((int)(mask))) & (int8)(1, 2, 4, 8, 16, 32, 64, 128)) != (int8)(0)))
#define co_c8_store(v, p) vstore8((v), 0, (p))
#else
typedef struct co_count8 {
  int32_t s[8];
} co_count8;
CO_INLINE co_count8 co_c8_zero(void) {
  co_count8 c;
  for (int i = 0; i < 8; ++i) c.s[i] = 0;
  return c;
}
CO_INLINE co_count8 co_c8_count(co_count8 c, uint32_t mask) {
  for (int i = 0; i < 8; ++i) c.s[i] += (int32_t)((mask >> i) & 1u);
  return c;
}
CO_INLINE void co_c8_store(co_count8 v, int32_t* p) {
  for (int i = 0; i < 8; ++i) p[i] = v.s[i];
}
#endif

/* A hint to start loading the cache line at p, where the host asks for it with -DCOHORT_PREFETCH
 * (devices whose local memory is the cached global memory: runtime/cl/kernel_program.cpp); GPUs hide
 * the latency with other warps. The form is chosen from what the compiler says it is, at program
 * build: Clang compiling straight to the machine (PoCL) takes Clang's builtin, which PoCL lowers to
 * a real prefetch where its OpenCL C prefetch() is a no-op; a compiler that goes through SPIR or
 * SPIR-V (Mesa's rusticl, whose SPIR-V writer stops the process at llvm.prefetch; Intel's runtime)
 * gets OpenCL C 1.2's own prefetch(), which every conforming compiler accepts. */
#if defined(__OPENCL_VERSION__)
#if defined(COHORT_PREFETCH) && defined(__clang__) && !defined(__SPIR__) && !defined(__SPIRV__) && \
    !defined(__SPIR32__) && !defined(__SPIR64__)
#define co_prefetch(p) __builtin_prefetch(p)
#elif defined(COHORT_PREFETCH)
#define co_prefetch(p) prefetch((p), 1)
#else
#define co_prefetch(p) ((void)(p))
#endif
#elif defined(__CUDACC__)
#define co_prefetch(p) ((void)(p))
#else
#define co_prefetch(p) __builtin_prefetch(p)
#endif

/* Bit counts on 32-bit words (the 8-wide BVH's hit masks, the 4-wide one's entered lanes): OpenCL C 1.2's
 * popcount and clz, CUDA's __popc and __clz, C++20's <bit> on the host. co_clz(0) is 32 on every side. */
#if defined(__OPENCL_VERSION__)
#define co_popcount(x) ((uint32_t)popcount((uint32_t)(x)))
#define co_clz(x) ((uint32_t)clz((uint32_t)(x)))
#elif defined(__CUDACC__)
#define co_popcount(x) ((uint32_t)__popc((unsigned int)(x)))
#define co_clz(x) ((uint32_t)__clz((int)(x)))
#else
#define co_popcount(x) ((uint32_t)std::popcount((uint32_t)(x)))
#define co_clz(x) ((uint32_t)std::countl_zero((uint32_t)(x)))
#endif

CO_INLINE uint32_t co_umin(uint32_t a, uint32_t b) { return a < b ? a : b; }
CO_INLINE uint32_t co_umax(uint32_t a, uint32_t b) { return a > b ? a : b; }

#endif
