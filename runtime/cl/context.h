// One device with its context and an in-order, profiling command queue.
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>
#include <string>

#include "runtime/cl/devices.h"

namespace cohort {

struct ClContext {
  DeviceInfo device;
  cl::Context context;
  cl::CommandQueue queue;

  explicit ClContext(const DeviceInfo& info);

  // A device buffer of `bytes` (at least 1), filled from `data` when given. Throws DeviceError naming
  // `what` and the sizes when the device cannot hold it.
  cl::Buffer buffer(const std::string& what, std::size_t bytes, const void* data = nullptr,
                    cl_mem_flags flags = CL_MEM_READ_WRITE) const;
};

// Seconds a finished kernel ran, from its profiling event.
double event_seconds(const cl::Event& event);

}  // namespace cohort
