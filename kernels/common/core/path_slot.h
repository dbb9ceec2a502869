/* The wavefront pool's path slot, declared once: one X-macro list from which the kernels' PathState,
 * load_path and store_path (wavefront_path.h), the PATH_BUFFERS kernel arguments (kernel_params.h),
 * the host's PathPool buffers (runtime/render/stages/path_pool.cpp) and PATH_STATE_BYTES are all
 * generated. Plain C: OpenCL C 1.2, CUDA and host C++ (no variadic macros: NVIDIA's OpenCL
 * compiler rejects them).
 *
 * PATH_SLOT(X, A) names each buffer of the slot (structure of arrays) as
 *   X(A, buffer, element type, vector width, state, field, w field, what)
 * - buffer: the kernel argument and host field is path_<buffer>; element type and vector width
 *   give its element (float, 4: co_float4; uint32_t, 1: uint32_t);
 * - state: how PathState holds it: VEC3 (a co_vec3 `field`, stored with w = 0), VEC3_W (a co_vec3
 *   `field` and, in the w lane, the scalar `w field`), VEC3_SEED (a co_vec3 `field` and, only with
 *   COHORT_FEATURE_ALPHA, the ray's uint32_t alpha seed `w field`, kept exactly in the w lane
 *   (accel/alpha_view.h); without it, as VEC3), VEC3_MEDIUM (a co_vec3 `field` and, only with
 *   COHORT_FEATURE_VOLUME, the path's uint32_t medium `w field`, kept exactly in the w lane as a
 *   float; without it, as VEC3), SCALAR (`field` itself) or SLOT_ONLY (not in PathState: the
 *   kernels read and write the buffer directly);
 * - what: the buffer's name on the host (allocation errors, -v).
 * A: passed through to X (PATH_BUFFERS passes the parameter macro of kernel_params.h). */
#ifndef COHORT_PATH_SLOT_H
#define COHORT_PATH_SLOT_H

#include "common/core/vec.h"

/* org: the ray's origin; with COHORT_FEATURE_ALPHA its w lane holds the ray's alpha seed, so that
 *   the PTH sort's payload, which moves the origin, moves the seed with the ray and the slot needs no
 *   buffer of its own for it;
 * throughput: with COHORT_FEATURE_VOLUME its w lane holds the medium the path is in (shading/medium.h:
 *   MEDIUM_NONE or 1 + a material index), so a volume costs the slot no byte; the PTH sort's
 *   payload (pth_gather) moves only the ray (org, dir), and shading reads the medium from the slot;
 * prev: the origin of the current ray (the last vertex, offset), for the MIS weight of emission,
 *   and the BSDF pdf that sampled it (0: the previous vertex was the camera);
 * item: the pass's work item the slot renders (ITEM_NONE: free), written by wf_generate;
 * segment: the segment `dir` traces (the camera ray is segment 1). */
#define PATH_SLOT(X, A)                                                                                    \
  X(A, org, float, 4, VEC3_SEED, org, alpha_seed, "path origins")                                          \
  X(A, dir, float, 4, VEC3, dir, _, "path directions")                                                     \
  X(A, throughput, float, 4, VEC3_MEDIUM, throughput, medium, "path throughput")                           \
  X(A, radiance, float, 4, VEC3, radiance, _, "path radiance")                                             \
  X(A, prev, float, 4, VEC3_W, prev_pos, prev_bsdf_pdf, "path previous vertex")                            \
  X(A, item, uint32_t, 1, SLOT_ONLY, _, _, "path work items")                                              \
  X(A, segment, uint32_t, 1, SCALAR, segment, _, "path segments")                                          \
  X(A, status, uint32_t, 1, SCALAR, status, _, "path status")

/* A buffer's element: CO_SLOT_TYPE(float, 4) is co_float4, CO_SLOT_TYPE(uint32_t, 1) uint32_t. */
#define CO_SLOT_TYPE(T, N) CO_SLOT_TYPE_##T##N
#define CO_SLOT_TYPE_float4 co_float4
#define CO_SLOT_TYPE_uint32_t1 uint32_t

/* ---- PathState: one path in registers ---------------------------------------------------------- */
#define CO_SLOT_MEMBER(A, buf, T, N, state, f, wf, what) CO_SLOT_MEMBER_##state(T, f, wf)
#define CO_SLOT_MEMBER_VEC3(T, f, wf) co_vec3 f;
#define CO_SLOT_MEMBER_VEC3_W(T, f, wf) co_vec3 f; T wf;
#if defined(COHORT_FEATURE_ALPHA)
#define CO_SLOT_MEMBER_VEC3_SEED(T, f, wf) co_vec3 f; uint32_t wf;
#else
#define CO_SLOT_MEMBER_VEC3_SEED(T, f, wf) co_vec3 f;
#endif
#if defined(COHORT_FEATURE_VOLUME)
#define CO_SLOT_MEMBER_VEC3_MEDIUM(T, f, wf) co_vec3 f; uint32_t wf;
#else
#define CO_SLOT_MEMBER_VEC3_MEDIUM(T, f, wf) co_vec3 f;
#endif
#define CO_SLOT_MEMBER_SCALAR(T, f, wf) T f;
#define CO_SLOT_MEMBER_SLOT_ONLY(T, f, wf)

typedef struct PathState {
  PATH_SLOT(CO_SLOT_MEMBER, _)
} PathState;

/* ---- Device bytes of one slot's path state ------------------------------------------------------ */
#define CO_SLOT_BYTES(A, buf, T, N, state, f, wf, what) + (uint32_t)(N * sizeof(T))
#define PATH_STATE_BYTES (0u PATH_SLOT(CO_SLOT_BYTES, _))
/* five float4 (origin with the alpha seed, direction, throughput with the medium, radiance, previous
 * vertex) and three uint (item, segment, status), with or without COHORT_FEATURE_ALPHA and
 * COHORT_FEATURE_VOLUME (their fields live in w lanes that are stored anyway): a change here changes
 * every method's pool size (device_pool_size) */
CO_STATIC_ASSERT(PATH_STATE_BYTES == 5u * 16u + 3u * 4u, "the path slot is 5 float4 and 3 uint");
CO_STATIC_ASSERT(sizeof(co_float4) == 4u * sizeof(float), "a float4 element is 4 floats");

#endif
