/* OpenCL entry point: BSDF queries for test/bsdf.
 * The kernels live in common/bsdf_test_kernel.h. */
#include "common/bsdf_test_kernel.h"
