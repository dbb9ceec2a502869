/* CUDA entry point: NAIVE megakernel.
 * The kernels live in common/naive_kernel.h. */
#include "common/naive_kernel.h"
