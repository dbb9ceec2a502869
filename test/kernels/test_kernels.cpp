#include "kernels/test_kernels.h"

namespace cohort {

std::string expand_test_kernel_source(std::string_view path) {
  return expand_kernel_source(path, test_kernel_sources());
}

ProgramBuild build_test_kernel_program(const ClContext& cl, const ProgramCache& cache, const std::string& file) {
  return build_cl_program(cl, cache, expand_test_kernel_source(file), base_build_options(cl.device));
}

}  // namespace cohort
