/* OpenCL entry point: wavefront stages.
 * The kernels live in common/wavefront_kernels.h. */
#include "common/wavefront_kernels.h"
