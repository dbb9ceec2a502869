#include "runtime/cl/devices.h"

#include <algorithm>

#include <fmt/format.h>

#include "runtime/cl/cl_error.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

// Drivers pad some strings with NULs; keep what a person would read.
std::string clean(std::string s) {
  s.erase(std::find(s.begin(), s.end(), '\0'), s.end());
  return s;
}

DeviceInfo describe_device(const cl::Platform& platform, const cl::Device& device, std::size_t pi, std::size_t di) {
  DeviceInfo info;
  info.platform_index = pi;
  info.device_index = di;
  info.platform_name = clean(platform.getInfo<CL_PLATFORM_NAME>());
  info.name = clean(device.getInfo<CL_DEVICE_NAME>());
  info.vendor = clean(device.getInfo<CL_DEVICE_VENDOR>());
  info.version = clean(device.getInfo<CL_DEVICE_VERSION>());
  info.driver_version = clean(device.getInfo<CL_DRIVER_VERSION>());
  const auto type = device.getInfo<CL_DEVICE_TYPE>();
  info.is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
  info.is_cpu = (type & CL_DEVICE_TYPE_CPU) != 0;
  info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  info.local_memory = device.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
  info.local_memory_is_global = device.getInfo<CL_DEVICE_LOCAL_MEM_TYPE>() == CL_GLOBAL;
  info.global_memory = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  info.max_allocation = device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  info.max_work_group = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
  const auto fp = device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>();
  info.correctly_rounded_divide_sqrt = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  info.denormals = (fp & CL_FP_DENORM) != 0;
  info.fma = (fp & CL_FP_FMA) != 0;
  info.subgroups = device.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_subgroups") != std::string::npos;
  info.image_support = device.getInfo<CL_DEVICE_IMAGE_SUPPORT>() != CL_FALSE;
  info.opencl_c_version = clean(device.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
  return info;
}

// Calls f(platform, device, platform index, device index) for every device, in platform order.
template <class F>
void for_each_device(F&& f) {
  std::vector<cl::Platform> platforms;
  // The ICD loader reports CL_PLATFORM_NOT_FOUND_KHR when nothing is installed: that is "no devices".
  // (returned or, with CL_HPP_ENABLE_EXCEPTIONS, thrown)
  try {
    if (cl::Platform::get(&platforms) != CL_SUCCESS) return;
  } catch (const cl::Error&) {
    return;
  }
  std::size_t index = 0;
  for (std::size_t pi = 0; pi < platforms.size(); ++pi) {
    std::vector<cl::Device> devices;
    try {
      platforms[pi].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices
    }
    for (const auto& d : devices) f(platforms[pi], d, pi, index++);
  }
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> out;
  try {
    for_each_device([&](const cl::Platform& p, const cl::Device& d, std::size_t pi, std::size_t index) {
      out.push_back(describe_device(p, d, pi, index));
    });
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, "listing OpenCL devices"));
  }
  return out;
}

std::vector<DeviceInfo> installed_devices() {
  auto devices = list_devices();
  if (devices.empty())
    throw InputError("no OpenCL device found: install an OpenCL driver (Debian: pocl-opencl-icd)");
  return devices;
}

DeviceInfo select_device(const std::string& spec) { return select_device(installed_devices(), spec); }

cl::Device find_cl_device(const DeviceInfo& info) {
  cl::Device found;
  try {
    for_each_device([&](const cl::Platform&, const cl::Device& d, std::size_t, std::size_t index) {
      if (index == info.device_index && clean(d.getInfo<CL_DEVICE_NAME>()) == info.name) found = d;
    });
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, info.name));
  }
  if (!found())
    throw DeviceError(fmt::format("OpenCL device {} ({}) is no longer listed", info.device_index, info.name));
  return found;
}

}  // namespace cohort
