/* CUDA entry point: traversal-only kernels for tests and ray benchmarks.
 * The kernels live in common/wavefront/trace_kernels.h. */
#include "common/wavefront/trace_kernels.h"
