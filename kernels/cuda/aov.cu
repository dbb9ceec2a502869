/* CUDA entry point: first-hit AOVs.
 * The kernel lives in common/wavefront/aov_kernel.h. */
#include "common/wavefront/aov_kernel.h"
