/* Path slots of the wavefront kernels (structure of arrays, PATH_SLOT in common/core/path_slot.h):
 * loads and stores of a PathState. Shared by wavefront_kernels.h and pth_kernels.h. */
#ifndef COHORT_WAVEFRONT_PATH_H
#define COHORT_WAVEFRONT_PATH_H

#include "common/core/kernel_params.h"
#include "common/wavefront/pathtrace.h"

#define PATH_PARAMS CO_PARAMS(PATH_BUFFERS)

/* load_path and store_path, one statement per entry of PATH_SLOT (common/core/path_slot.h), in
 * its order; a SLOT_ONLY buffer (the work item) is neither loaded nor stored. */
#define CO_SLOT_LOAD(A, buf, T, N, state, f, wf, what) CO_SLOT_LOAD_##state(buf, f, wf)
#define CO_SLOT_LOAD_VEC3(buf, f, wf) st.f = v3_from4(path_##buf[slot]);
#define CO_SLOT_LOAD_VEC3_W(buf, f, wf)                                                                     \
  {                                                                                                        \
    co_float4 v = path_##buf[slot];                                                                        \
    st.f = v3_from4(v);                                                                                    \
    st.wf = v.w;                                                                                            \
  }
#if defined(COHORT_FEATURE_ALPHA)
#define CO_SLOT_LOAD_VEC3_SEED(buf, f, wf)                                                                  \
  {                                                                                                        \
    co_float4 v = path_##buf[slot];                                                                        \
    st.f = v3_from4(v);                                                                                    \
    st.wf = alpha_seed_from_float(v.w);                                                                    \
  }
#else
#define CO_SLOT_LOAD_VEC3_SEED(buf, f, wf) CO_SLOT_LOAD_VEC3(buf, f, wf)
#endif
#if defined(COHORT_FEATURE_VOLUME)
#define CO_SLOT_LOAD_VEC3_MEDIUM(buf, f, wf)                                                                \
  {                                                                                                        \
    co_float4 v = path_##buf[slot];                                                                        \
    st.f = v3_from4(v);                                                                                    \
    st.wf = (uint32_t)v.w;                                                                                  \
  }
#else
#define CO_SLOT_LOAD_VEC3_MEDIUM(buf, f, wf) CO_SLOT_LOAD_VEC3(buf, f, wf)
#endif
#define CO_SLOT_LOAD_SCALAR(buf, f, wf) st.f = path_##buf[slot];
#define CO_SLOT_LOAD_SLOT_ONLY(buf, f, wf)

CO_INLINE PathState load_path(PATH_PARAMS, uint32_t slot) {
  PathState st;
  PATH_SLOT(CO_SLOT_LOAD, _)
  return st;
}

CO_INLINE co_float4 to4(co_vec3 v, float w) { return co_make_float4(v.x, v.y, v.z, w); }

#define CO_SLOT_STORE(A, buf, T, N, state, f, wf, what) CO_SLOT_STORE_##state(buf, f, wf)
#define CO_SLOT_STORE_VEC3(buf, f, wf) path_##buf[slot] = to4(st->f, 0.0f);
#define CO_SLOT_STORE_VEC3_W(buf, f, wf) path_##buf[slot] = to4(st->f, st->wf);
#if defined(COHORT_FEATURE_ALPHA)
#define CO_SLOT_STORE_VEC3_SEED(buf, f, wf) path_##buf[slot] = to4(st->f, alpha_seed_to_float(st->wf));
#else
#define CO_SLOT_STORE_VEC3_SEED(buf, f, wf) CO_SLOT_STORE_VEC3(buf, f, wf)
#endif
#if defined(COHORT_FEATURE_VOLUME)
/* the medium, 1 + a material index below 2^24 (device_scene.cpp checks), is exact as a float */
#define CO_SLOT_STORE_VEC3_MEDIUM(buf, f, wf) path_##buf[slot] = to4(st->f, (float)st->wf);
#else
#define CO_SLOT_STORE_VEC3_MEDIUM(buf, f, wf) CO_SLOT_STORE_VEC3(buf, f, wf)
#endif
#define CO_SLOT_STORE_SCALAR(buf, f, wf) path_##buf[slot] = st->f;
#define CO_SLOT_STORE_SLOT_ONLY(buf, f, wf)

CO_INLINE void store_path(PATH_PARAMS, uint32_t slot, const PathState *st) {
  PATH_SLOT(CO_SLOT_STORE, _)
}

#define PATH_ARGS CO_ARGS(PATH_BUFFERS)

/* The slot a launch index stands for: the compacted queue's entry, or the index itself. */
CO_INLINE uint32_t slot_of(uint32_t i, CO_GLOBAL const uint32_t *queue, uint32_t use_queue) {
  return use_queue ? queue[i] : i;
}

/* The work items of a launch over `count` indices: with the compacted queue, only the live slots
 * the device counted (the host launches over the whole pool and never reads the count). */
CO_INLINE uint32_t launch_count(uint32_t count, CO_GLOBAL const uint32_t *counters, uint32_t use_queue) {
  return use_queue ? co_umin(count, counters[COUNTER_QUEUE]) : count;
}

/* Work item `item` of a pass: sample item / n of the pass's pixel item % n (n: the pass's pixels). */
CO_INLINE uint32_t pixel_of(uint32_t item, CO_GLOBAL const uint32_t *pixel_list, const RenderParams *p) {
  return pass_pixel(item % pass_pixel_count(p), pixel_list, p);
}
CO_INLINE uint32_t sample_of(uint32_t item, const RenderParams *p) {
  return p->sample_offset + item / pass_pixel_count(p);
}

#endif
