#include "runtime/cuda/nvrtc_compile.h"

#include <sstream>

#include <fmt/format.h>

#include "runtime/cuda/cuda_api.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

void check(nvrtcResult r, const char* what) {
  if (r != NVRTC_SUCCESS) throw DeviceError(fmt::format("{} failed: {}", what, nvrtc().nvrtcGetErrorString(r)));
}

// Destroys the NVRTC program on every path out.
struct ProgramHandle {
  nvrtcProgram program = nullptr;
  ~ProgramHandle() {
    if (program) nvrtc().nvrtcDestroyProgram(&program);
  }
};

}  // namespace

std::vector<std::string> nvrtc_options(int cc_major, int cc_minor, const std::string& defines) {
  // kept in step with COHORT_CUDA_ROUNDING_FLAGS in CMakeLists.txt
  std::vector<std::string> options = {fmt::format("--gpu-architecture=sm_{}{}", cc_major, cc_minor), "--std=c++17",
                                      "--fmad=false", "--prec-div=true", "--prec-sqrt=true", "--ftz=false"};
  std::istringstream in(defines);
  for (std::string word; in >> word;) options.push_back(word);
  return options;
}

std::string nvrtc_compile(const std::string& name, const std::string& source, const std::vector<std::string>& options) {
  const Nvrtc& n = nvrtc();
  ProgramHandle h;
  const std::string file = "cuda/" + name + ".cu";
  check(n.nvrtcCreateProgram(&h.program, source.c_str(), file.c_str(), 0, nullptr, nullptr), "nvrtcCreateProgram");
  std::vector<const char*> argv;
  for (const auto& o : options) argv.push_back(o.c_str());
  const nvrtcResult compiled = n.nvrtcCompileProgram(h.program, static_cast<int>(argv.size()), argv.data());
  if (compiled != NVRTC_SUCCESS) {
    std::size_t size = 0;
    n.nvrtcGetProgramLogSize(h.program, &size);
    std::string log(size, '\0');
    if (size) n.nvrtcGetProgramLog(h.program, log.data());
    throw DeviceError(fmt::format("NVRTC could not compile {}: {}\n{}", file, n.nvrtcGetErrorString(compiled), log));
  }
  std::size_t size = 0;
  check(n.nvrtcGetCUBINSize(h.program, &size), "nvrtcGetCUBINSize");
  std::string cubin(size, '\0');
  check(n.nvrtcGetCUBIN(h.program, cubin.data()), "nvrtcGetCUBIN");
  return cubin;
}

std::string nvrtc_version() {
  int major = 0, minor = 0;
  check(nvrtc().nvrtcVersion(&major, &minor), "nvrtcVersion");
  return fmt::format("{}.{}", major, minor);
}

}  // namespace cohort
