#include "runtime/cl/context.h"

#include <cstring>

#include <fmt/format.h>

#include "runtime/cl/cl_error.h"
#include "runtime/cl/devices.h"
#include "runtime/cl/host_pages.h"

namespace cohort {

ClContext::ClContext(const DeviceInfo& info) : device(info), cl_device(find_cl_device(info)) {
  try {
    context = cl::Context(cl_device);
    queue = cl::CommandQueue(context, cl_device, CL_QUEUE_PROFILING_ENABLE);
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, device.name));
  }
}

cl::Buffer ClContext::buffer(const std::string& what, std::size_t bytes, const void* data, cl_mem_flags flags) const {
  bytes = std::max<std::size_t>(bytes, 1);
  if (bytes > device.max_allocation)
    throw DeviceError(fmt::format("{} needs {} bytes in one buffer; {} allows at most {} bytes per allocation", what,
                                  bytes, device.name, device.max_allocation));
  if (device.is_cpu && !is_oclgrind(device) && bytes >= kHugePageBytes / 2)
    return host_page_buffer(what, bytes, data, flags);
  try {
    // Drivers may defer a buffer's allocation and its CL_MEM_COPY_HOST_PTR upload to the first
    // kernel that uses it (NVIDIA's does), which put the scene's upload inside the first pass.
    // A blocking write uploads now; a migration places a buffer without contents on the device.
    cl::Buffer b(context, flags, bytes);
    if (data)
      queue.enqueueWriteBuffer(b, CL_TRUE, 0, bytes, data);
    else
      queue.enqueueMigrateMemObjects({b}, CL_MIGRATE_MEM_OBJECT_CONTENT_UNDEFINED);
    return b;
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, fmt::format("{}, {} bytes", what, bytes)));
  }
}

cl::Buffer ClContext::host_page_buffer(const std::string& what, std::size_t bytes, const void* data,
                                       cl_mem_flags flags) const {
  void* memory = allocate_huge_pages(bytes);
  if (!memory)
    throw DeviceError(fmt::format("{} needs {} bytes of host memory for {}, which could not be allocated", what, bytes,
                                  device.name));
  try {
    if (data) std::memcpy(memory, data, bytes);
    cl::Buffer b(context, flags | CL_MEM_USE_HOST_PTR, bytes, memory);
    // the memory goes when the driver releases the buffer, however many handles shared it
    b.setDestructorCallback([](cl_mem, void* m) { free_huge_pages(m); }, memory);
    return b;
  } catch (const cl::Error& e) {
    free_huge_pages(memory);
    throw DeviceError(describe(e, fmt::format("{}, {} bytes", what, bytes)));
  }
}

double event_seconds(const cl::Event& event) {
  const auto start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const auto end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-9;
}

}  // namespace cohort
