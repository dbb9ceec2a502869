// OpenCL platforms and devices: listing them as DeviceInfo, and finding one again.
#pragma once

#include <CL/opencl.hpp>

#include <string>
#include <vector>

#include "runtime/backend/device_choice.h"
#include "runtime/backend/device_info.h"

namespace cohort {

// Every device of every platform, in platform order. Empty when no platform is installed.
std::vector<DeviceInfo> list_devices();

// list_devices(), or InputError naming the driver to install when it is empty.
std::vector<DeviceInfo> installed_devices();

// select_device's rule (runtime/backend/device_choice.h) over installed_devices().
DeviceInfo select_device(const std::string& spec);

// The OpenCL device that list_devices() described as `info`. Throws DeviceError when it is gone.
cl::Device find_cl_device(const DeviceInfo& info);

}  // namespace cohort
