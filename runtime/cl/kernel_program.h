// Builds one of the embedded .cl programs for a device, through the cache.
#pragma once

#include <string>

#include "runtime/cl/context.h"
#include "runtime/cl/program_cache.h"

namespace cohort {

// Options every program shares: the same language level and no fast-math, so every method
// compiles the shared shading and traversal code identically.
std::string base_build_options();

ProgramBuild build_kernel_program(const ClContext& cl, const ProgramCache& cache, const std::string& file,
                                  const std::string& extra_options = {});

}  // namespace cohort
