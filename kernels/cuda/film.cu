/* CUDA entry point: the image film kept on the device. The kernel lives in common/film_kernels.h. */
#include "common/film_kernels.h"
