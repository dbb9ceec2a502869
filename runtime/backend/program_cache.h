// An on-disk cache of compiled program binaries, keyed by device, driver, options and source; each
// backend builds through it (runtime/cl/kernel_program.h, runtime/cuda/cuda_device.cpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "runtime/backend/device_info.h"

namespace cohort {

class ProgramCache {
 public:
  // directory: where binaries live; std::nullopt turns the cache off.
  explicit ProgramCache(std::optional<std::filesystem::path> directory);

  // $COHORT_CACHE_DIR, else $XDG_CACHE_HOME/cohort/kernels, else ~/.cache/cohort/kernels.
  static std::filesystem::path default_directory();

  // The cache key text: device, driver, options and a hash of the source.
  static std::string key(const DeviceInfo& device, const std::string& source, const std::string& options);

  // Any backend's binaries: the entry stored under `key`, or nothing when the cache is off or the
  // entry is absent, damaged or of another key; store() never fails (a read-only or full cache
  // directory costs speed, not correctness). A backend rebuilds an entry its driver rejects.
  std::optional<std::string> load(const std::string& key) const;
  void store(const std::string& key, const std::string& binary) const;

  // Where the entry of `key` lives; nothing when the cache is off.
  std::optional<std::filesystem::path> entry_file(const std::string& key) const;

 private:
  std::optional<std::filesystem::path> directory_;
};

}  // namespace cohort
