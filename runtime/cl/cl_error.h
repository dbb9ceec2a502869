// Turns OpenCL errors into messages that name the failing call and the error.
#pragma once

#include <CL/opencl.hpp>

#include <stdexcept>
#include <string>

#include "runtime/util/error.h"

namespace cohort {

const char* cl_error_name(cl_int code);

std::string describe(const cl::Error& e, const std::string& context = {});

}  // namespace cohort
