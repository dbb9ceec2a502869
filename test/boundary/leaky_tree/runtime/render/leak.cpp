// The boundary check's own test: each include below is a leak it must report.
#include "runtime/backend/device.h"
#include <CL/opencl.hpp>
#  include "runtime/cl/context.h"
#include <cuda.h>
#include "runtime/cuda/cuda_api.h"
