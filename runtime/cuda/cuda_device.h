// The CUDA implementation of the backend interface (runtime/backend/device.h): the driver API on
// one GPU's primary context and one stream, kernels compiled by NVRTC from the embedded sources.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "runtime/backend/device.h"

namespace cohort {

// CUDA GPUs, described as DeviceInfo (platform "CUDA"). Throws InputError when there is no driver.
std::vector<DeviceInfo> list_cuda_devices();

// "" picks GPU 0; otherwise an index or a case-insensitive substring of the name. `memory_limit`
// (bytes, 0 = none) caps the memory the renderers may plan with. Throws InputError when no GPU
// matches or none is usable.
std::unique_ptr<Device> open_cuda_device(const std::string& spec, std::uint64_t memory_limit = 0);

}  // namespace cohort
