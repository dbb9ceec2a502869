// What the renderers plan with about a device, whichever backend lists it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace cohort {

struct DeviceInfo {
  std::size_t platform_index = 0;  // OpenCL: the platform's index; CUDA: 0
  std::size_t device_index = 0;  // index in its backend's list, as `cohort devices` prints it
  std::string platform_name;     // the OpenCL platform; "CUDA"
  std::string name;
  std::string vendor;
  std::string version;         // OpenCL: CL_DEVICE_VERSION; CUDA: the compute capability
  std::string driver_version;
  bool is_gpu = false;
  bool is_cpu = false;
  std::uint32_t compute_units = 0;
  std::uint64_t local_memory = 0;
  bool local_memory_is_global = false;  // PoCL: "local" memory is ordinary cached memory
  std::uint64_t global_memory = 0;
  std::uint64_t max_allocation = 0;
  std::size_t max_work_group = 0;
  bool correctly_rounded_divide_sqrt = false;  // OpenCL: CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT
  bool subgroups = false;                      // OpenCL: cl_khr_subgroups (sub-group votes)
  bool denormals = true;                       // OpenCL: CL_FP_DENORM in the single-precision config
  bool fma = true;                             // OpenCL: CL_FP_FMA (a fused multiply-add in hardware)
  bool image_support = false;                  // OpenCL: CL_DEVICE_IMAGE_SUPPORT (Cohort reads textures from buffers)
  std::string opencl_c_version;                // OpenCL: CL_DEVICE_OPENCL_C_VERSION; empty for CUDA
};

// The simulator of scripts/test-oclgrind, whose checks need host-side detours: whole-buffer writes
// and fills (runtime/cl/cl_device.cpp), buffers the driver allocates itself (runtime/cl/context.cpp),
// and no prefetch (it checks the kernels, never times them: device_support).
inline bool is_oclgrind(const DeviceInfo& d) { return d.platform_name == "Oclgrind"; }
inline bool is_pocl(const DeviceInfo& d) { return d.platform_name == "Portable Computing Language"; }

}  // namespace cohort
