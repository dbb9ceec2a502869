/* CUDA entry point: BSDF queries for test/bsdf.
 * The kernels live in bsdf_test_kernel.h. */
#include "bsdf_test_kernel.h"
