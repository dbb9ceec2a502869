// The CUDA driver API and NVRTC, loaded with dlopen at run time: cohort never links libcuda or
// libnvrtc, so it starts on machines without an NVIDIA driver, and `--backend cuda` there fails
// with a message instead.
#pragma once

#include <cuda.h>
#include <nvrtc.h>

#include <string>

namespace cohort {

// Each X(name) is a function of cuda.h; cuda.h maps some names to versioned symbols
// (cuMemAlloc -> cuMemAlloc_v2), and the loader looks up the same symbol the header declares.
#define COHORT_CUDA_DRIVER_FUNCTIONS(X)                                                                         \
  X(cuInit) X(cuDriverGetVersion) X(cuDeviceGetCount) X(cuDeviceGet) X(cuDeviceGetName) X(cuDeviceGetAttribute) \
  X(cuDeviceTotalMem) X(cuDevicePrimaryCtxRetain) X(cuDevicePrimaryCtxRelease) X(cuCtxSetCurrent)              \
  X(cuStreamCreate) X(cuStreamDestroy) X(cuStreamSynchronize) X(cuMemAlloc) X(cuMemFree)                       \
  X(cuMemcpyHtoDAsync) X(cuMemcpyDtoHAsync) X(cuMemcpyDtoDAsync) X(cuMemsetD32Async) X(cuModuleLoadData)       \
  X(cuModuleUnload) X(cuModuleGetFunction) X(cuFuncGetAttribute) X(cuLaunchKernel) X(cuEventCreate)            \
  X(cuEventDestroy) X(cuEventRecord) X(cuEventSynchronize) X(cuEventElapsedTime) X(cuGetErrorName)

#define COHORT_NVRTC_FUNCTIONS(X)                                                                       \
  X(nvrtcVersion) X(nvrtcCreateProgram) X(nvrtcDestroyProgram) X(nvrtcCompileProgram) X(nvrtcGetProgramLogSize) \
  X(nvrtcGetProgramLog) X(nvrtcGetCUBINSize) X(nvrtcGetCUBIN) X(nvrtcGetErrorString)

struct CudaDriver {
#define COHORT_DECLARE(f) decltype(&::f) f = nullptr;
  COHORT_CUDA_DRIVER_FUNCTIONS(COHORT_DECLARE)
#undef COHORT_DECLARE
  // Throws DeviceError naming `what` and the error when `result` is not CUDA_SUCCESS.
  void check(CUresult result, const std::string& what) const;
};

struct Nvrtc {
#define COHORT_DECLARE(f) decltype(&::f) f = nullptr;
  COHORT_NVRTC_FUNCTIONS(COHORT_DECLARE)
#undef COHORT_DECLARE
};

// The driver, loaded and initialised once. Throws InputError (exit code 2) when there is none: no
// libcuda.so.1, or cuInit fails (no GPU, driver mismatch), with the reason.
const CudaDriver& cuda_driver();

// NVRTC, loaded once. Throws InputError when libnvrtc cannot be loaded.
const Nvrtc& nvrtc();

}  // namespace cohort
