#include "runtime/cl/kernel_program.h"

#include "runtime/cl/embedded_sources.h"

namespace cohort {

std::string base_build_options() { return "-cl-std=CL1.2"; }

ProgramBuild build_kernel_program(const ClContext& cl, const ProgramCache& cache, const std::string& file,
                                  const std::string& extra_options) {
  std::string options = base_build_options();
  if (!extra_options.empty()) options += " " + extra_options;
  return cache.build(cl.context, cl.device, expand_kernel_source(file), options);
}

}  // namespace cohort
