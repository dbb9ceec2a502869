// A third implementation of the backend interface, for tests: the shared kernels compiled as plain
// host C++ (kernels/common/core/port.h's host branch) and run one work item at a time. The renderers, the
// sort and the tracing helpers run on it unchanged, so comparing it with OpenCL on PoCL checks the
// shared code through a C++ compiler, the path CUDA's code takes, on a machine without a GPU.
//
// Work-groups run with one work item (barriers are then no-ops): the sort is built with the CPU
// tiling (SORT_WG = 1), and the other kernels share local memory only for the PTH
// subtree copy, which one work item does alone.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "runtime/backend/device.h"

namespace cohort::test {

// One host kernel: runs the work item set in co_host_item with the launch's arguments.
using HostKernelFunction = std::function<void(const std::vector<KernelArg>& args)>;
using HostProgramTable = std::map<std::string, HostKernelFunction>;

// Kernel tables of the programs compiled into the test (host_kernels_*.cpp); `defines` is what the
// compiled-in program was built with (the sort's tiling), checked against what the caller asks for.
struct HostProgram {
  std::string defines;  // the only defines build_program accepts besides -DCOHORT_FEATURE_*
  HostProgramTable kernels;
};
const HostProgram& host_render_program();  // naive, wavefront, pth and trace kernels
const HostProgram& host_sort64_program();  // radix_sort, SORT_WG=1 SORT_ITEMS=4096, 64-bit keys
const HostProgram& host_sort32_program();  // the same for 32-bit keys

class HostDevice final : public Device {
 public:
  HostDevice();
  Backend backend() const override { return Backend::opencl; }  // not a user-visible backend
  const DeviceInfo& info() const override { return info_; }
  DeviceBuffer allocate(const std::string& what, std::size_t bytes, const void* data = nullptr,
                        Access access = Access::read_write) const override;
  DeviceProgram compile_program(const ProgramCache& cache, const std::string& name,
                                const std::string& defines) const override;
  void write(const DeviceBuffer& to, std::size_t offset, std::size_t bytes, const void* data,
             bool blocking = true) const override;
  void read(const DeviceBuffer& from, std::size_t offset, std::size_t bytes, void* data) const override;
  DeviceEvent copy(const DeviceBuffer& from, const DeviceBuffer& to, std::size_t bytes) const override;
  void fill(const DeviceBuffer& to, std::uint32_t value, std::size_t count) const override;
  void finish() const override {}

 protected:
  DeviceEvent enqueue(const DeviceKernel& kernel, std::size_t items, std::size_t group) const override;

 private:
  DeviceInfo info_;
};

// The host memory of a HostDevice buffer.
unsigned char* host_bytes(const DeviceBuffer& b);

// Adapts a kernel entry point (a host function of plain types and pointers) to HostKernelFunction:
// pointer parameters take buffers (or local memory), the others values, in order.
template <class... Params>
HostKernelFunction host_kernel(void (*entry)(Params...));

}  // namespace cohort::test

#include "host/host_kernel_adapter.h"
