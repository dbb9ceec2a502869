/* The image film kept on the device when one device renders every pass (runtime/render/
 * pass_driver.cpp): each pass's partial film is added to it with the float additions, in the
 * order, that combining on the host makes, so the image is the same bits either way. Each
 * work-group also sums its pixels of the pass (for the pass's mean, a statistic only), and the
 * entry after the groups' carries the pass's dropped-sample count. */
#ifndef COHORT_FILM_KERNELS_H
#define COHORT_FILM_KERNELS_H

#include "common/core/kernel_params.h"

CO_KERNEL film_add(CO_PARAMS(FILM_ADD_PARAMS)) {
  CO_SHARED float sum_x[FILM_WG];
  CO_SHARED float sum_y[FILM_WG];
  CO_SHARED float sum_z[FILM_WG];
  uint32_t i = co_global_id(), l = co_local_id();
  co_float4 p = co_make_float4(0.0f, 0.0f, 0.0f, 0.0f);
  if (i < pixels) {
    p = pass[i];
    co_float4 t = image[i];
    t.x = t.x + p.x;
    t.y = t.y + p.y;
    t.z = t.z + p.z;
    t.w = t.w + p.w;
    image[i] = t;
  }
  sum_x[l] = p.x;
  sum_y[l] = p.y;
  sum_z[l] = p.z;
  co_barrier();
  for (uint32_t stride = co_local_size() / 2u; stride > 0u; stride >>= 1) {
    if (l < stride) {
      sum_x[l] += sum_x[l + stride];
      sum_y[l] += sum_y[l + stride];
      sum_z[l] += sum_z[l + stride];
    }
    co_barrier();
  }
  if (l == 0u) group_sums[co_group_id()] = co_make_float4(sum_x[0], sum_y[0], sum_z[0], 0.0f);
  /* the pass's dropped-sample count rides along, so the host reads the pass back in one call */
  if (i == 0u) group_sums[groups] = co_make_float4(co_as_float(dropped[0]), 0.0f, 0.0f, 0.0f);
}

#endif
