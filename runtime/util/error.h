// Error types that main() turns into exit codes: InputError -> 2 (bad usage or input), anything else -> 1.
#pragma once

#include <stdexcept>
#include <string>

namespace cohort {

// Bad input or usage: the message names the file (or option) and what is wrong.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A device call failed; what() names the call, the error and the context, e.g.
// "clEnqueueNDRangeKernel failed (render_naive pass): CL_OUT_OF_RESOURCES (-5)".
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace cohort
