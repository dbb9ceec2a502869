/* The eight-lane counters of common/core/port.h (co_count8) as a device compiles them, for
 * test/cl/trace_kernel_test.cpp: co_c8_count over `n` masks, then each lane's count. */
#include "common/core/port.h"

__kernel void count8_test(__global const uint* masks, uint n, __global int* out) {
  if (get_global_id(0) != 0) return;
  co_count8 c = co_c8_zero();
  for (uint i = 0; i < n; ++i) c = co_c8_count(c, masks[i]);
  int counted[8];
  co_c8_store(c, counted);
  for (int l = 0; l < 8; ++l) out[l] = counted[l];
}
