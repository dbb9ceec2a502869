// The CUDA backend includes CUDA (allowed) but not OpenCL (lines 4 and 5 leak).
#include <cuda.h>
#include "runtime/cuda/cuda_api.h"
#include <CL/cl.h>
#include "runtime/cl/devices.h"
