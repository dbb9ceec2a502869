// Turns OpenCL errors into messages that name the failing call and the error.
#pragma once

#include <CL/opencl.hpp>

#include <stdexcept>
#include <string>

namespace cohort {

const char* cl_error_name(cl_int code);

// An OpenCL call failed; what() reads like
// "clEnqueueNDRangeKernel failed (render_naive pass): CL_OUT_OF_RESOURCES (-5)".
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string describe(const cl::Error& e, const std::string& context = {});

}  // namespace cohort
