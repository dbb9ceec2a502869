// OpenCL platforms and devices: listing and choosing one.
#pragma once

#include <CL/opencl.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace cohort {

struct DeviceInfo {
  std::size_t platform_index = 0;
  std::size_t device_index = 0;  // global index over all platforms, as `cohort devices` prints it
  std::string platform_name;
  std::string name;
  std::string vendor;
  std::string version;         // CL_DEVICE_VERSION
  std::string driver_version;  // CL_DRIVER_VERSION
  bool is_gpu = false;
  bool is_cpu = false;
  std::uint32_t compute_units = 0;
  std::uint64_t local_memory = 0;
  bool local_memory_is_global = false;  // PoCL: "local" memory is ordinary cached memory
  std::uint64_t global_memory = 0;
  std::uint64_t max_allocation = 0;
  std::size_t max_work_group = 0;
  bool correctly_rounded_divide_sqrt = false;  // CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT
  cl::Device device;
};

// Every device of every platform, in platform order. Empty when no platform is installed.
std::vector<DeviceInfo> list_devices();

// "" picks the device $COHORT_DEVICE names (any spec below; how the tests and scripts/test-vendors
// choose a runtime), else the first GPU, else the first CPU device; otherwise an index into list_devices() or a
// case-insensitive substring of the device or platform name. Throws InputError when nothing matches.
DeviceInfo select_device(const std::string& spec);

// Several devices: "all" (every device), "all:NAME" (every device whose device or platform name
// contains NAME), "rank:NAME" (of the devices matching NAME, the one at this process's rank among
// the MPI ranks of its machine, modulo their count: one GPU per rank), or a comma list of single
// specs as select_device takes them, each naming a different device (a repeated name picks the
// next device that matches). One spec without a comma is select_device's choice. Throws
// InputError when an item matches nothing new.
std::vector<DeviceInfo> select_devices(const std::string& spec, int local_rank = 0);

}  // namespace cohort
