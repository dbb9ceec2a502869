// The one file that chooses a backend: it may include both.
#include "runtime/cl/context.h"
#include "runtime/cuda/cuda_device.h"
