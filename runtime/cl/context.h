// One device with its context and an in-order, profiling command queue: the OpenCL backend.
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>
#include <string>

#include "runtime/backend/device.h"
#include "runtime/cl/devices.h"

namespace cohort {

struct ClContext : Device {
  DeviceInfo device;
  cl::Device cl_device;  // the device list_devices() described as `device`
  cl::Context context;
  cl::CommandQueue queue;

  explicit ClContext(const DeviceInfo& info);

  // A device buffer of `bytes` (at least 1), filled from `data` when given. Throws DeviceError naming
  // `what` and the sizes when the device cannot hold it.
  cl::Buffer buffer(const std::string& what, std::size_t bytes, const void* data = nullptr,
                    cl_mem_flags flags = CL_MEM_READ_WRITE) const;

  // On a CPU device: a buffer in host memory of 2 MiB pages (runtime/cl/host_pages.h), which the
  // kernels read in place (CL_MEM_USE_HOST_PTR).
  cl::Buffer host_page_buffer(const std::string& what, std::size_t bytes, const void* data, cl_mem_flags flags) const;

  // The backend interface (runtime/backend/device.h).
  Backend backend() const override { return Backend::opencl; }
  const DeviceInfo& info() const override { return device; }
  DeviceBuffer allocate(const std::string& what, std::size_t bytes, const void* data = nullptr,
                        Access access = Access::read_write) const override;
  DeviceProgram compile_program(const ProgramCache& cache, const std::string& name,
                                const std::string& defines) const override;
  std::string compile_options() const override;
  DeviceEvent enqueue(const DeviceKernel& kernel, std::size_t items, std::size_t group) const override;
  void write(const DeviceBuffer& to, std::size_t offset, std::size_t bytes, const void* data,
             bool blocking = true) const override;
  void read(const DeviceBuffer& from, std::size_t offset, std::size_t bytes, void* data) const override;
  DeviceEvent copy(const DeviceBuffer& from, const DeviceBuffer& to, std::size_t bytes) const override;
  void fill(const DeviceBuffer& to, std::uint32_t value, std::size_t count) const override;
  void finish() const override;
};

// Device::launch's work-group size (launch_group) for a kernel launched outside the backend
// interface (tests that set cl::Kernel arguments themselves).
std::size_t cl_launch_group(const cl::Kernel& kernel, const cl::Device& device, std::size_t wanted = 0);

// The OpenCL buffer behind a buffer of the OpenCL backend.
const cl::Buffer& cl_buffer(const DeviceBuffer& b);

// Seconds a finished kernel ran, from its profiling event.
double event_seconds(const cl::Event& event);

}  // namespace cohort
