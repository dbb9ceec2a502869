/* CUDA entry point: partial traversal and resumed traversal (methods pth and hash).
 * The kernels live in common/pth/pth_kernels.h. */
#include "common/pth/pth_kernels.h"
