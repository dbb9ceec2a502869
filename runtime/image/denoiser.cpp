// OIDN's C API through dlopen: only the dozen entry points the RT filter needs, declared here from
// OIDN 2's oidn.h, so no OIDN header or package is needed at build time.
#include "runtime/image/denoiser.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <system_error>

namespace cohort {
// Named, not anonymous: Denoiser::Api (a class with linkage) holds these types.
namespace oidn {

using OIDNDevice = struct OIDNDeviceImpl*;
using OIDNFilter = struct OIDNFilterImpl*;
constexpr int kDeviceTypeCpu = 1;  // OIDN_DEVICE_TYPE_CPU
constexpr int kFormatFloat3 = 3;   // OIDN_FORMAT_FLOAT3
constexpr int kErrorNone = 0;      // OIDN_ERROR_NONE

// Closes the library when the last Denoiser copy goes.
struct LibraryHandle {
  void* handle = nullptr;
  explicit LibraryHandle(void* h) : handle(h) {}
  LibraryHandle(const LibraryHandle&) = delete;
  LibraryHandle& operator=(const LibraryHandle&) = delete;
  ~LibraryHandle() {
    if (handle) dlclose(handle);
  }
};

}  // namespace oidn

struct Denoiser::Api {
  using LibraryHandle = oidn::LibraryHandle;
  using OIDNDevice = oidn::OIDNDevice;
  using OIDNFilter = oidn::OIDNFilter;
  std::unique_ptr<LibraryHandle> library;
  std::string path;
  OIDNDevice (*new_device)(int) = nullptr;
  void (*commit_device)(OIDNDevice) = nullptr;
  void (*release_device)(OIDNDevice) = nullptr;
  int (*device_error)(OIDNDevice, const char**) = nullptr;
  OIDNFilter (*new_filter)(OIDNDevice, const char*) = nullptr;
  void (*set_shared_image)(OIDNFilter, const char*, void*, int, std::size_t, std::size_t, std::size_t, std::size_t,
                           std::size_t) = nullptr;
  void (*set_filter_bool)(OIDNFilter, const char*, bool) = nullptr;
  void (*commit_filter)(OIDNFilter) = nullptr;
  void (*execute_filter)(OIDNFilter) = nullptr;
  void (*release_filter)(OIDNFilter) = nullptr;
};

namespace {

template <class F>
void bind(void* library, const std::string& path, const char* name, F& out) {
  void* symbol = dlsym(library, name);
  if (!symbol) throw DenoiserUnavailable(fmt::format("{} has no {}: not Open Image Denoise 2", path, name));
  out = reinterpret_cast<F>(symbol);
}

}  // namespace

std::vector<std::filesystem::path> Denoiser::venv_candidates(const std::filesystem::path& venv) {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  const std::filesystem::path lib = venv / "lib";
  if (!std::filesystem::is_directory(lib, ec)) return out;
  for (const auto& python : std::filesystem::directory_iterator(lib, ec)) {
    const auto candidate = python.path() / "site-packages/pyoidn/oidn/lib/libOpenImageDenoise.so.2";
    if (std::filesystem::exists(candidate, ec)) out.push_back(candidate);
  }
  return out;
}

Denoiser Denoiser::load(const std::vector<std::filesystem::path>& extra_candidates) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("COHORT_OIDN_LIBRARY"); env && *env) {
    candidates.emplace_back(env);  // named by the user: that library or none
  } else {
    candidates.emplace_back("libOpenImageDenoise.so.2");
    for (const auto& p : extra_candidates) candidates.push_back(p.string());
  }
  std::string tried;
  for (const std::string& path : candidates) {
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      tried += fmt::format("\n  {}: {}", path, why ? why : "not found");
      continue;
    }
    auto api = std::make_shared<Api>();
    api->library = std::make_unique<oidn::LibraryHandle>(handle);
    api->path = path;
    bind(handle, path, "oidnNewDevice", api->new_device);
    bind(handle, path, "oidnCommitDevice", api->commit_device);
    bind(handle, path, "oidnReleaseDevice", api->release_device);
    bind(handle, path, "oidnGetDeviceError", api->device_error);
    bind(handle, path, "oidnNewFilter", api->new_filter);
    bind(handle, path, "oidnSetSharedFilterImage", api->set_shared_image);
    bind(handle, path, "oidnSetFilterBool", api->set_filter_bool);
    bind(handle, path, "oidnCommitFilter", api->commit_filter);
    bind(handle, path, "oidnExecuteFilter", api->execute_filter);
    bind(handle, path, "oidnReleaseFilter", api->release_filter);
    return Denoiser(std::move(api));
  }
  throw DenoiserUnavailable(
      "Open Image Denoise was not found (set COHORT_OIDN_LIBRARY to a libOpenImageDenoise.so.2, run scripts/render "
      "or scripts/test, which install the pyoidn wheel from PyPI into build/venv, or `pip install pyoidn` into the "
      "Python environment that imports cohort); tried:" +
      tried);
}

const std::string& Denoiser::library() const { return api_->path; }

Image Denoiser::denoise(const Image& beauty, const Image* albedo, const Image* normal) const {
  using namespace oidn;
  const Api& api = *api_;
  auto same_size = [&](const Image* guide, const char* name) {
    if (guide && (guide->width != beauty.width || guide->height != beauty.height))
      throw std::invalid_argument(fmt::format("denoise: {} is {}x{}, the image {}x{}", name, guide->width,
                                              guide->height, beauty.width, beauty.height));
  };
  same_size(albedo, "albedo");
  same_size(normal, "normal");
  if (normal && !albedo) throw std::invalid_argument("denoise: a normal guide needs an albedo guide too");
  Image out(beauty.width, beauty.height);
  if (beauty.rgb.empty()) return out;

  // RAII for the device and the filter: released on every path out
  const std::unique_ptr<OIDNDeviceImpl, void (*)(OIDNDevice)> device(api.new_device(kDeviceTypeCpu),
                                                                     api.release_device);
  auto check = [&](const char* step) {
    const char* message = nullptr;
    if (api.device_error(device.get(), &message) != kErrorNone)
      throw DenoiserUnavailable(fmt::format("Open Image Denoise ({}): {} failed: {}", api.path, step,
                                            message ? message : "unknown error"));
  };
  if (!device) throw DenoiserUnavailable(fmt::format("Open Image Denoise ({}): no CPU device", api.path));
  api.commit_device(device.get());
  check("creating the CPU device");
  const std::unique_ptr<OIDNFilterImpl, void (*)(OIDNFilter)> filter(api.new_filter(device.get(), "RT"),
                                                                     api.release_filter);
  check("creating the RT filter");
  const auto w = static_cast<std::size_t>(beauty.width), h = static_cast<std::size_t>(beauty.height);
  // OIDN reads the shared inputs only; the const_casts hand it the pointers its C API asks for
  api.set_shared_image(filter.get(), "color", const_cast<float*>(beauty.rgb.data()), kFormatFloat3, w, h, 0, 0, 0);
  if (albedo)
    api.set_shared_image(filter.get(), "albedo", const_cast<float*>(albedo->rgb.data()), kFormatFloat3, w, h, 0, 0, 0);
  if (normal)
    api.set_shared_image(filter.get(), "normal", const_cast<float*>(normal->rgb.data()), kFormatFloat3, w, h, 0, 0, 0);
  api.set_shared_image(filter.get(), "output", out.rgb.data(), kFormatFloat3, w, h, 0, 0, 0);
  api.set_filter_bool(filter.get(), "hdr", true);
  api.commit_filter(filter.get());
  check("setting up the RT filter");
  api.execute_filter(filter.get());
  check("denoising");
  return out;
}

}  // namespace cohort
