// The OpenCL backend includes OpenCL (allowed) but not CUDA (line 4 leaks).
#include <CL/opencl.hpp>
#include "runtime/cl/devices.h"
#include <nvrtc.h>
