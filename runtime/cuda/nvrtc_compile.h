// Compiles an embedded CUDA program (kernels/cuda/NAME.cu) with NVRTC: the same shared kernel
// headers and defines as the OpenCL build, CUDA's rounding flags, for one GPU architecture.
#pragma once

#include <string>
#include <vector>

namespace cohort {

// The options NVRTC gets: the architecture (sm_XY), the rounding that matches OpenCL and the host
// (no FMA contraction, IEEE division and square root, denormals kept) and `defines` split at spaces.
std::vector<std::string> nvrtc_options(int cc_major, int cc_minor, const std::string& defines);

// The CUBIN of kernels/cuda/NAME.cu. Throws DeviceError with NVRTC's log when it does not compile,
// InputError when NVRTC cannot be loaded.
std::string nvrtc_compile(const std::string& name, const std::string& source, const std::vector<std::string>& options);

// NVRTC's version as "MAJOR.MINOR", for cache keys.
std::string nvrtc_version();

}  // namespace cohort
