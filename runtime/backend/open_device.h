// Opens the device a command runs on, from --backend and --device.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "runtime/backend/device.h"

namespace cohort {

// "opencl" or "cuda"; throws InputError naming the choices otherwise.
Backend parse_backend(const std::string& name);

// Whether this build has the CUDA backend (nvcc was found when it was configured).
bool cuda_backend_built();

// OpenCL: `spec` as select_device (runtime/cl/devices.h); CUDA: an index or a substring of the GPU's
// name, "" for the first. `memory_limit` (bytes, 0 = none) caps the device memory the renderers plan
// with. Throws InputError (exit code 2) when the backend has no usable device, with the reason.
// The devices of `backend` (what --device indexes). Throws InputError when the backend has none usable.
std::vector<DeviceInfo> list_backend_devices(Backend backend);

std::unique_ptr<Device> open_device(Backend backend, const std::string& spec, std::uint64_t memory_limit = 0);

}  // namespace cohort
