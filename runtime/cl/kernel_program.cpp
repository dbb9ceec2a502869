#include "runtime/cl/kernel_program.h"

#include <chrono>

#include <fmt/format.h>

#include "runtime/backend/device_support.h"
#include "runtime/backend/embedded_sources.h"
#include "runtime/cl/cl_error.h"
#include "runtime/cl/devices.h"

namespace cohort {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string build_log(const cl::Program& program, const cl::Device& device) {
  try {
    return program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
  } catch (const cl::Error&) {
    return "(no build log)";
  }
}

}  // namespace

std::string base_build_options(const DeviceInfo& device) {
  std::string options = "-cl-std=CL1.2";
  if (device.correctly_rounded_divide_sqrt) options += " -cl-fp32-correctly-rounded-divide-sqrt";
  // software prefetch in the BVH walk and paired walks where device_support says so (port.h's
  // co_prefetch picks its form from the compiler)
  const DeviceSupport support = device_support(device);
  if (support.prefetch) options += " -DCOHORT_PREFETCH";
  if (support.paired_walks) options += " -DCOHORT_PAIRED_WALKS";
  if (!support.fused_slabs) options += " -DCOHORT_UNFUSED_SLABS";
  if (support.branch_free_descend) options += " -DCOHORT_BRANCH_FREE_DESCEND";
  if (support.gpu_minmax) options += " -DCOHORT_GPU_MINMAX";
  if (support.pixel_tiles) options += " -DCOHORT_PIXEL_TILES";
  return options;
}

ProgramBuild build_cl_program(const ClContext& cl, const ProgramCache& cache, const std::string& source,
                              const std::string& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string entry_key = ProgramCache::key(cl.device, source, options);
  ProgramBuild result;
  if (const auto file = cache.entry_file(entry_key)) {
    result.cache_file = file->string();
    if (auto binary = cache.load(entry_key)) {
      try {
        cl::Program::Binaries binaries{std::vector<unsigned char>(binary->begin(), binary->end())};
        cl::Program program(cl.context, {cl.cl_device}, binaries);
        program.build({cl.cl_device}, options.c_str());
        result.program = program;
        result.from_cache = true;
        result.seconds = seconds_since(t0);
        return result;
      } catch (const cl::Error&) {
        // the driver rejected the cached binary (a new driver, a damaged file): rebuild below
      }
    }
  }
  cl::Program program;
  try {
    program = cl::Program(cl.context, source);
    program.build({cl.cl_device}, options.c_str());
  } catch (const cl::Error& e) {
    throw DeviceError(fmt::format("{} on {}:\n{}", describe(e), cl.device.name, build_log(program, cl.cl_device)));
  }
  result.program = program;
  result.seconds = seconds_since(t0);
  if (!result.cache_file.empty()) {
    try {
      const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
      if (!binaries.empty() && !binaries.front().empty())
        cache.store(entry_key, std::string(binaries.front().begin(), binaries.front().end()));
    } catch (const cl::Error&) {
      // a driver that cannot return its binary costs speed, not correctness
    }
  }
  return result;
}

ProgramBuild build_kernel_program(const ClContext& cl, const ProgramCache& cache, const std::string& file,
                                  const std::string& extra_options) {
  std::string options = base_build_options(cl.device);
  if (!extra_options.empty()) options += " " + extra_options;
  return build_cl_program(cl, cache, expand_kernel_source(file), options);
}

}  // namespace cohort
