/* CUDA entry point: first-hit AOVs.
 * The kernel lives in common/aov_kernel.h. */
#include "common/aov_kernel.h"
