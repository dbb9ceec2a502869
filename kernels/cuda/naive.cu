/* CUDA entry point: NAIVE megakernel.
 * The kernels live in common/wavefront/naive_kernel.h. */
#include "common/wavefront/naive_kernel.h"
