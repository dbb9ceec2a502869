// Builds OpenCL programs (the embedded .cl files, or any source) for a device, through the cache.
#pragma once

#include <CL/opencl.hpp>

#include <string>

#include "runtime/backend/device_info.h"
#include "runtime/backend/program_cache.h"
#include "runtime/cl/context.h"

namespace cohort {

struct ProgramBuild {
  cl::Program program;
  bool from_cache = false;  // warm: loaded from a cached binary
  double seconds = 0;       // compile (cold) or load (warm) time
  std::string cache_file;   // empty when the cache is off
};

// Options every program shares: the same language level, no fast-math, and IEEE division and
// square root where the device offers them (NVIDIA's defaults are approximate), so every method
// compiles the shared shading and traversal code identically and the host, which rounds
// correctly, computes the same bits.
std::string base_build_options(const DeviceInfo& device);

// Builds `source` with `options` for the context's device. A cache entry whose header, key or
// checksum does not match, or that the driver rejects, is rebuilt and replaced, never trusted.
// Throws DeviceError with the build log when the source does not compile.
ProgramBuild build_cl_program(const ClContext& cl, const ProgramCache& cache, const std::string& source,
                              const std::string& options);

// The embedded `file` with base_build_options and extra_options: the scene's -DCOHORT_FEATURE_*
// defines (DeviceScene::build_options) for the rendering programs; they join the cache key with the
// rest of the options.
ProgramBuild build_kernel_program(const ClContext& cl, const ProgramCache& cache, const std::string& file,
                                  const std::string& extra_options = {});

}  // namespace cohort
