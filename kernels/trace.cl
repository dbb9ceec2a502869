/* OpenCL entry point: traversal-only kernels for tests and ray benchmarks.
 * The kernels live in common/trace_kernels.h. */
#include "common/trace_kernels.h"
