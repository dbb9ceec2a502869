// The one file that chooses a backend: allowed.
#include "runtime/cl/context.h"
#include "runtime/cuda/cuda_device.h"
