// Intel Open Image Denoise (OIDN 2), loaded at run time with dlopen: Cohort builds and runs without
// it, and `--denoise` says clearly when it cannot be found.
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/image/image.h"

namespace cohort {

// OIDN could not be loaded or used; the message says where it looked or what failed.
struct DenoiserUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Denoiser {
 public:
  // Loads $COHORT_OIDN_LIBRARY when set (that file only), else the first of the system's
  // libOpenImageDenoise.so.2 and `extra_candidates` (for example the pyoidn wheel's copy in the
  // project's virtual environment, which scripts/test installs). Throws DenoiserUnavailable.
  static Denoiser load(const std::vector<std::filesystem::path>& extra_candidates = {});

  // The pyoidn wheel's library under a virtual environment, if it is there.
  static std::vector<std::filesystem::path> venv_candidates(const std::filesystem::path& venv);

  // OIDN's "RT" filter over a linear HDR image, guided by the first-hit albedo and the world-space
  // shading normal when given (both or neither; same size as `beauty`). Returns a new image; the
  // input is untouched. Throws DenoiserUnavailable with OIDN's message when the filter fails.
  Image denoise(const Image& beauty, const Image* albedo = nullptr, const Image* normal = nullptr) const;

  const std::string& library() const;  // the file it was loaded from

 private:
  struct Api;
  explicit Denoiser(std::shared_ptr<const Api> api) : api_(std::move(api)) {}
  std::shared_ptr<const Api> api_;
};

}  // namespace cohort
