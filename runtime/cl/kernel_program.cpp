#include "runtime/cl/kernel_program.h"

#include "runtime/cl/embedded_sources.h"

namespace cohort {

std::string base_build_options(const DeviceInfo& device) {
  std::string options = "-cl-std=CL1.2";
  if (device.correctly_rounded_divide_sqrt) options += " -cl-fp32-correctly-rounded-divide-sqrt";
  return options;
}

ProgramBuild build_kernel_program(const ClContext& cl, const ProgramCache& cache, const std::string& file,
                                  const std::string& extra_options) {
  std::string options = base_build_options(cl.device);
  if (!extra_options.empty()) options += " " + extra_options;
  return cache.build(cl.context, cl.device, expand_kernel_source(file), options);
}

}  // namespace cohort
