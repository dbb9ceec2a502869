/* OpenCL entry point: NAIVE megakernel.
 * The kernels live in common/wavefront/naive_kernel.h. */
/* box tests with min and max instructions on GPUs (common/core/port.h) */
#define COHORT_PROGRAM_MINMAX 1
#include "common/wavefront/naive_kernel.h"
