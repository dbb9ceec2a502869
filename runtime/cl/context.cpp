#include "runtime/cl/context.h"

#include <fmt/format.h>

#include "runtime/cl/cl_error.h"

namespace cohort {

ClContext::ClContext(const DeviceInfo& info) : device(info) {
  try {
    context = cl::Context(device.device);
    queue = cl::CommandQueue(context, device.device, CL_QUEUE_PROFILING_ENABLE);
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, device.name));
  }
}

cl::Buffer ClContext::buffer(const std::string& what, std::size_t bytes, const void* data, cl_mem_flags flags) const {
  bytes = std::max<std::size_t>(bytes, 1);
  if (bytes > device.max_allocation)
    throw DeviceError(fmt::format("{} needs {} bytes in one buffer; {} allows at most {} bytes per allocation", what,
                                  bytes, device.name, device.max_allocation));
  try {
    if (data) return cl::Buffer(context, flags | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(data));
    cl::Buffer b(context, flags, bytes);
    return b;
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, fmt::format("{}, {} bytes", what, bytes)));
  }
}

double event_seconds(const cl::Event& event) {
  const auto start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const auto end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-9;
}

}  // namespace cohort
