/* BSDF sample/eval/pdf for a buffer of queries: lets test/bsdf/ run its checks on the device and
 * compare with the host, which runs the same bsdf_test_run() on the same inputs. */
#ifndef COHORT_BSDF_TEST_KERNEL_H
#define COHORT_BSDF_TEST_KERNEL_H

#include "bsdf_test_io.h"

CO_KERNEL bsdf_test(CO_GLOBAL const BsdfTestIn* in, CO_GLOBAL BsdfTestOut* out, uint32_t count) {
  uint32_t i = co_global_id();
  if (i >= count) return;
  BsdfTestIn q = in[i];
  out[i] = bsdf_test_run(&q);
}

#endif
