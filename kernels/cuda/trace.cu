/* CUDA entry point: traversal-only kernels for tests and ray benchmarks.
 * The kernels live in common/wavefront/trace_kernels.h. */
/* box tests with min and max instructions on GPUs (common/core/port.h) */
#define COHORT_PROGRAM_MINMAX 1
#include "common/wavefront/trace_kernels.h"
