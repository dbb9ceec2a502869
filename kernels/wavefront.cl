/* OpenCL entry point: wavefront stages.
 * The kernels live in common/wavefront/wavefront_kernels.h. */
#include "common/wavefront/wavefront_kernels.h"
