/* Path slots of the wavefront kernels (structure of arrays, PATH_BUFFERS in kernel_params.h): loads
 * and stores of a PathState. Shared by wavefront_kernels.h and pth_kernels.h. */
#ifndef COHORT_WAVEFRONT_PATH_H
#define COHORT_WAVEFRONT_PATH_H

#include "common/core/kernel_params.h"
#include "common/wavefront/pathtrace.h"

#define PATH_PARAMS CO_PARAMS(PATH_BUFFERS)

CO_INLINE PathState load_path(PATH_PARAMS, uint32_t slot) {
  PathState st;
  st.org = v3_from4(path_org[slot]);
  st.dir = v3_from4(path_dir[slot]);
  st.throughput = v3_from4(path_throughput[slot]);
  st.radiance = v3_from4(path_radiance[slot]);
  co_float4 prev = path_prev[slot];
  st.prev_pos = v3_from4(prev);
  st.prev_bsdf_pdf = prev.w;
  st.segment = path_segment[slot];
  st.status = path_status[slot];
  return st;
}

CO_INLINE co_float4 to4(co_vec3 v, float w) { return co_make_float4(v.x, v.y, v.z, w); }

CO_INLINE void store_path(PATH_PARAMS, uint32_t slot, const PathState *st) {
  path_org[slot] = to4(st->org, 0.0f);
  path_dir[slot] = to4(st->dir, 0.0f);
  path_throughput[slot] = to4(st->throughput, 0.0f);
  path_radiance[slot] = to4(st->radiance, 0.0f);
  path_prev[slot] = to4(st->prev_pos, st->prev_bsdf_pdf);
  path_segment[slot] = st->segment;
  path_status[slot] = st->status;
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
