// Builds one of the embedded .cl programs for a device, through the cache.
#pragma once

#include <string>

#include "runtime/cl/context.h"
#include "runtime/cl/devices.h"
#include "runtime/cl/program_cache.h"

namespace cohort {

// Options every program shares: the same language level, no fast-math, and IEEE division and
// square root where the device offers them (NVIDIA's defaults are approximate), so every method
// compiles the shared shading and traversal code identically and the host, which rounds
// correctly, computes the same bits.
std::string base_build_options(const DeviceInfo& device);

// extra_options: the scene's -DCOHORT_FEATURE_* defines (DeviceScene::build_options) for the
// rendering programs; they join the cache key with the rest of the options.
ProgramBuild build_kernel_program(const ClContext& cl, const ProgramCache& cache, const std::string& file,
                                  const std::string& extra_options = {});

}  // namespace cohort
