#include "runtime/cuda/cuda_api.h"

#include <dlfcn.h>

#include <cstdlib>
#include <vector>

#include <fmt/format.h>

#include "runtime/util/error.h"

namespace cohort {
namespace {

#define COHORT_STR2(x) #x
#define COHORT_STR(x) COHORT_STR2(x)

// A library handle that lives as long as the process: the function pointers point into it.
void* open_library(const std::vector<std::string>& names, std::string& tried) {
  for (const auto& name : names) {
    if (void* h = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL)) return h;
    const char* err = dlerror();  // names the library already
    tried += fmt::format("\n  {}", err ? err : name + ": not found");
  }
  return nullptr;
}

// The symbol cuda.h declares, else the unversioned name (older drivers lack some _v2 entries).
void* find_symbol(void* library, const char* versioned, const char* plain) {
  if (void* p = dlsym(library, versioned)) return p;
  return dlsym(library, plain);
}

std::string unversioned(std::string name) {
  if (const auto v = name.rfind("_v"); v != std::string::npos && v + 2 < name.size()) name.resize(v);
  return name;
}

CudaDriver load_driver() {
  std::string tried;
  void* lib = open_library({"libcuda.so.1", "libcuda.so"}, tried);
  if (!lib)
    throw InputError(fmt::format("--backend cuda: no usable CUDA GPU: the NVIDIA driver could not be loaded:{}", tried));
  CudaDriver d;
#define COHORT_LOAD(f)                                                                                  \
  d.f = reinterpret_cast<decltype(d.f)>(find_symbol(lib, COHORT_STR(f), unversioned(COHORT_STR(f)).c_str())); \
  if (!d.f) throw InputError(fmt::format("--backend cuda: the NVIDIA driver lacks {}", COHORT_STR(f)));
  COHORT_CUDA_DRIVER_FUNCTIONS(COHORT_LOAD)
#undef COHORT_LOAD
  if (const CUresult r = d.cuInit(0); r != CUDA_SUCCESS) {
    const char* name = nullptr;
    d.cuGetErrorName(r, &name);
    throw InputError(fmt::format("--backend cuda: no usable CUDA GPU: cuInit failed: {} ({})",
                                 name ? name : "unknown error", static_cast<int>(r)));
  }
  return d;
}

Nvrtc load_nvrtc() {
  std::vector<std::string> names = {"libnvrtc.so.13", "libnvrtc.so.12", "libnvrtc.so"};
  for (const char* var : {"CUDA_PATH", "CUDA_HOME"})
    if (const char* dir = std::getenv(var); dir && *dir) names.push_back(fmt::format("{}/lib64/libnvrtc.so", dir));
  names.push_back("/usr/local/cuda/lib64/libnvrtc.so");
  std::string tried;
  void* lib = open_library(names, tried);
  if (!lib)
    throw InputError(fmt::format("--backend cuda: NVRTC, which compiles the kernels, could not be loaded (install "
                                 "the CUDA toolkit or put its lib64 on LD_LIBRARY_PATH):{}",
                                 tried));
  Nvrtc n;
#define COHORT_LOAD(f)                                                    \
  n.f = reinterpret_cast<decltype(n.f)>(dlsym(lib, COHORT_STR(f)));       \
  if (!n.f) throw InputError(fmt::format("--backend cuda: NVRTC lacks {}", COHORT_STR(f)));
  COHORT_NVRTC_FUNCTIONS(COHORT_LOAD)
#undef COHORT_LOAD
  return n;
}

}  // namespace

void CudaDriver::check(CUresult result, const std::string& what) const {
  if (result == CUDA_SUCCESS) return;
  const char* name = nullptr;
  if (cuGetErrorName) cuGetErrorName(result, &name);
  throw DeviceError(fmt::format("{} failed: {} ({})", what, name ? name : "unknown CUDA error", static_cast<int>(result)));
}

// Loaded on first use and never changed after: a function-local static, initialised thread-safely.
const CudaDriver& cuda_driver() {
  static const CudaDriver driver = load_driver();
  return driver;
}

const Nvrtc& nvrtc() {
  static const Nvrtc n = load_nvrtc();
  return n;
}

}  // namespace cohort
