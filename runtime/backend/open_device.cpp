#include "runtime/backend/open_device.h"

#include <algorithm>

#include <fmt/format.h>

#include "runtime/backend/device_choice.h"
#include "runtime/backend/device_support.h"
#include "runtime/cl/context.h"
#include "runtime/util/error.h"
#ifdef COHORT_WITH_CUDA
#include "runtime/cuda/cuda_device.h"
#endif

namespace cohort {

Backend parse_backend(const std::string& name) {
  if (name == "opencl") return Backend::opencl;
  if (name == "cuda") return Backend::cuda;
  throw InputError("--backend " + name + ": unknown backend (choose from opencl, cuda)");
}

bool cuda_backend_built() {
#ifdef COHORT_WITH_CUDA
  return true;
#else
  return false;
#endif
}

std::vector<DeviceInfo> list_backend_devices(Backend backend) {
  if (backend == Backend::opencl) return installed_devices();
#ifdef COHORT_WITH_CUDA
  return list_cuda_devices();
#else
  throw InputError("this build has no CUDA backend (nvcc was not found when it was configured)");
#endif
}

std::unique_ptr<Device> open_device(Backend backend, const std::string& spec, std::uint64_t memory_limit) {
  if (backend == Backend::cuda) {
#ifdef COHORT_WITH_CUDA
    return open_cuda_device(spec, memory_limit);
#else
    throw InputError("--backend cuda: this build has no CUDA backend (nvcc was not found when it was configured)");
#endif
  }
  DeviceInfo device = select_device(installed_devices(), spec);
  if (const DeviceSupport support = device_support(device); !support.runs)
    throw InputError(fmt::format("--device {}: Cohort cannot run on {}", spec.empty() ? "(default)" : spec, support.refusal));
  if (memory_limit) {
    device.global_memory = std::min(device.global_memory, memory_limit);
    device.max_allocation = std::min(device.max_allocation, memory_limit);
  }
  return std::make_unique<ClContext>(device);
}

DeviceOpener opencl_opener(const std::vector<DeviceInfo>& devices) {
  return [devices](std::size_t i) -> std::unique_ptr<Device> { return std::make_unique<ClContext>(devices.at(i)); };
}

}  // namespace cohort
