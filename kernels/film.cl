/* OpenCL entry point: the image film kept on the device. The kernel lives in common/film/film_kernels.h. */
#include "common/film/film_kernels.h"
