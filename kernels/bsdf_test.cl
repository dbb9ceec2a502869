/* BSDF sample/eval/pdf for a buffer of queries: lets test/bsdf/ run its checks on the device and
 * compare with the host, which runs the same bsdf_test_run() on the same inputs. */
#include "common/bsdf_test_io.h"

__kernel void bsdf_test(__global const BsdfTestIn* in, __global BsdfTestOut* out, uint count) {
  uint i = get_global_id(0);
  if (i >= count) return;
  BsdfTestIn q = in[i];
  out[i] = bsdf_test_run(&q);
}
