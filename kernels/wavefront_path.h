/* Path slots of the wavefront kernels (OpenCL C): the structure-of-arrays layout, its kernel
 * parameters, and loads and stores of a PathState. Shared by wavefront.cl and pth.cl. */
#ifndef COHORT_WAVEFRONT_PATH_H
#define COHORT_WAVEFRONT_PATH_H

#include "common/pathtrace.h"

#define ITEM_NONE 0xffffffffu

/* counters[] */
#define COUNTER_NEXT_ITEM 0
#define COUNTER_QUEUE 1   /* live slots (and the length of the compacted queue) */
#define COUNTER_SHADOW 2  /* shadow rays queued this bounce */
#define COUNTER_SIMD_SUM 3
#define COUNTER_SIMD_GROUPS 4

#define PATH_PARAMS                                                                                  \
  __global float4 *path_org, __global float4 *path_dir, __global float4 *path_throughput,            \
      __global float4 *path_radiance, __global float4 *path_prev, __global uint *path_item,          \
      __global uint *path_segment, __global uint *path_status

inline PathState load_path(PATH_PARAMS, uint slot) {
  PathState st;
  st.org = v3_from4(path_org[slot]);
  st.dir = v3_from4(path_dir[slot]);
  st.throughput = v3_from4(path_throughput[slot]);
  st.radiance = v3_from4(path_radiance[slot]);
  float4 prev = path_prev[slot];
  st.prev_pos = v3_from4(prev);
  st.prev_bsdf_pdf = prev.w;
  st.segment = path_segment[slot];
  st.status = path_status[slot];
  return st;
}

inline float4 to4(co_vec3 v, float w) { return (float4)(v.x, v.y, v.z, w); }

inline void store_path(PATH_PARAMS, uint slot, const PathState* st) {
  path_org[slot] = to4(st->org, 0.0f);
  path_dir[slot] = to4(st->dir, 0.0f);
  path_throughput[slot] = to4(st->throughput, 0.0f);
  path_radiance[slot] = to4(st->radiance, 0.0f);
  path_prev[slot] = to4(st->prev_pos, st->prev_bsdf_pdf);
  path_segment[slot] = st->segment;
  path_status[slot] = st->status;
}

#define PATH_ARGS path_org, path_dir, path_throughput, path_radiance, path_prev, path_item, path_segment, path_status

/* The slot a launch index stands for: the compacted queue's entry, or the index itself. */
inline uint slot_of(uint i, __global const uint* queue, uint use_queue) { return use_queue ? queue[i] : i; }

inline uint pixel_of(uint item, const RenderParams* p) { return item % (p->width * p->height); }
inline uint sample_of(uint item, const RenderParams* p) { return p->sample_offset + item / (p->width * p->height); }

#endif
