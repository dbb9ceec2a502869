// Opens the device a command runs on, from --backend and --device: the one place that knows both
// backends (runtime/cl, runtime/cuda).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/backend/device.h"

namespace cohort {

// "opencl" or "cuda"; throws InputError naming the choices otherwise.
Backend parse_backend(const std::string& name);

// Whether this build has the CUDA backend (nvcc was found when it was configured).
bool cuda_backend_built();

// The devices of `backend` (what --device indexes). Throws InputError when the backend has none usable.
std::vector<DeviceInfo> list_backend_devices(Backend backend);

// OpenCL: `spec` as select_device (runtime/backend/device_choice.h); CUDA: an index or a substring of
// the GPU's name, "" for the first. `memory_limit` (bytes, 0 = none) caps the device memory the
// renderers plan with. Throws InputError (exit code 2) when the backend has no usable device, with
// the reason.
std::unique_ptr<Device> open_device(Backend backend, const std::string& spec, std::uint64_t memory_limit = 0);

// Opens device `index` of a list on the calling thread (a CUDA context is current on the thread
// that made it, so each worker opens its own).
using DeviceOpener = std::function<std::unique_ptr<Device>(std::size_t index)>;

// OpenCL contexts for `devices`, entries of list_backend_devices(Backend::opencl).
DeviceOpener opencl_opener(const std::vector<DeviceInfo>& devices);

}  // namespace cohort
