// Turns OpenCL errors into messages that name the failing call and the error.
#pragma once

#include <CL/opencl.hpp>

#include <stdexcept>
#include <string>

#include "runtime/util/error.h"

namespace cohort {

const char* cl_error_name(cl_int code);

std::string describe(const cl::Error& e, const std::string& context = {});

// Returns call(), an OpenCL error turned into DeviceError (describe(e, context)): OpenCL's own errors
// stay inside the backend.
template <class Call>
decltype(auto) translate_cl_errors(Call&& call, const char* context = "") {
  try {
    return call();
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, context));
  }
}

}  // namespace cohort
