// The OpenCL backend includes OpenCL: allowed.
#include <CL/opencl.hpp>
