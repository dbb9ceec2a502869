#include "runtime/cl/devices.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>

#include <fmt/format.h>

#include "runtime/util/error.h"

namespace cohort {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Drivers pad some strings with NULs; keep what a person would read.
std::string clean(std::string s) {
  s.erase(std::find(s.begin(), s.end(), '\0'), s.end());
  return s;
}

DeviceInfo describe(const cl::Platform& platform, const cl::Device& device, std::size_t pi, std::size_t di) {
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
  info.correctly_rounded_divide_sqrt =
      (device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  info.device = device;
  return info;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<cl::Platform> platforms;
  // The ICD loader reports CL_PLATFORM_NOT_FOUND_KHR when nothing is installed: that is "no devices".
  // (returned or, with CL_HPP_ENABLE_EXCEPTIONS, thrown)
  try {
    if (cl::Platform::get(&platforms) != CL_SUCCESS) return {};
  } catch (const cl::Error&) {
    return {};
  }
  std::vector<DeviceInfo> out;
  for (std::size_t pi = 0; pi < platforms.size(); ++pi) {
    std::vector<cl::Device> devices;
    try {
      platforms[pi].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices
    }
    for (const auto& d : devices) out.push_back(describe(platforms[pi], d, pi, out.size()));
  }
  return out;
}

namespace {

bool name_matches(const DeviceInfo& d, const std::string& needle) {
  return lower(d.name).find(needle) != std::string::npos || lower(d.platform_name).find(needle) != std::string::npos;
}

std::vector<DeviceInfo> installed_devices() {
  auto devices = list_devices();
  if (devices.empty())
    throw InputError("no OpenCL device found: install an OpenCL driver (Debian: pocl-opencl-icd)");
  return devices;
}

// select_device's rule over `devices`, skipping those already `taken`.
DeviceInfo pick(const std::vector<DeviceInfo>& devices, const std::string& spec, const std::vector<bool>& taken) {
  if (spec.empty()) {
    for (const auto& d : devices)
      if (d.is_gpu) return d;
    for (const auto& d : devices)
      if (d.is_cpu) return d;
    return devices.front();
  }
  std::size_t index = 0;
  const auto [ptr, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), index);
  if (ec == std::errc() && ptr == spec.data() + spec.size()) {
    if (index < devices.size()) return devices[index];
    throw InputError(fmt::format("--device {}: there are only {} devices (see `cohort devices`)", spec,
                                 devices.size()));
  }
  const auto needle = lower(spec);
  for (const auto& d : devices)
    if (!taken[d.device_index] && name_matches(d, needle)) return d;
  throw InputError(fmt::format("--device {}: no {}device name matches (see `cohort devices`)", spec,
                               std::count(taken.begin(), taken.end(), true) ? "other " : ""));
}

// An empty --device means $COHORT_DEVICE when it is set.
std::string device_spec(const std::string& spec) {
  if (!spec.empty()) return spec;
  const char* env = std::getenv("COHORT_DEVICE");
  return env ? env : "";
}

}  // namespace

DeviceInfo select_device(const std::string& requested) {
  const std::string spec = device_spec(requested);
  const auto devices = installed_devices();
  return pick(devices, spec, std::vector<bool>(devices.size(), false));
}

std::vector<DeviceInfo> select_devices(const std::string& requested, int local_rank) {
  const std::string spec = device_spec(requested);
  const auto devices = installed_devices();
  if (spec == "all" || spec.starts_with("all:") || spec.starts_with("rank:")) {
    const std::size_t colon = spec.find(':');
    const std::string needle = lower(colon == std::string::npos ? "" : spec.substr(colon + 1));
    std::vector<DeviceInfo> chosen;
    for (const auto& d : devices)
      if (name_matches(d, needle)) chosen.push_back(d);
    if (chosen.empty()) throw InputError(fmt::format("--device {}: no device name matches (see `cohort devices`)", spec));
    if (spec.starts_with("rank:")) return {chosen[static_cast<std::size_t>(std::max(local_rank, 0)) % chosen.size()]};
    return chosen;
  }
  std::vector<bool> taken(devices.size(), false);
  std::vector<DeviceInfo> chosen;
  std::size_t start = 0;
  do {
    const std::size_t comma = spec.find(',', start);
    const std::string item = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty() && spec.find(',') != std::string::npos)
      throw InputError(fmt::format("--device {}: an empty item in the list", spec));
    DeviceInfo d = pick(devices, item, taken);
    if (taken[d.device_index]) throw InputError(fmt::format("--device {}: device {} is listed twice", spec, item));
    taken[d.device_index] = true;
    chosen.push_back(std::move(d));
    start = comma == std::string::npos ? std::string::npos : comma + 1;
  } while (start != std::string::npos);
  return chosen;
}

}  // namespace cohort
