// Builds OpenCL programs through an on-disk cache of program binaries.
#pragma once

#include <CL/opencl.hpp>

#include <filesystem>
#include <optional>
#include <string>

#include "runtime/cl/devices.h"

namespace cohort {

struct ProgramBuild {
  cl::Program program;
  bool from_cache = false;  // warm: loaded from a cached binary
  double seconds = 0;       // compile (cold) or load (warm) time
  std::string cache_file;   // empty when the cache is off
};

class ProgramCache {
 public:
  // directory: where binaries live; std::nullopt turns the cache off.
  explicit ProgramCache(std::optional<std::filesystem::path> directory);

  // $COHORT_CACHE_DIR, else $XDG_CACHE_HOME/cohort/kernels, else ~/.cache/cohort/kernels.
  static std::filesystem::path default_directory();

  // Builds `source` with `options` for the device. A cache entry whose header, key or checksum does
  // not match, or that the driver rejects, is rebuilt and replaced, never trusted. Throws
  // DeviceError with the build log when the source does not compile.
  ProgramBuild build(const cl::Context& context, const DeviceInfo& device, const std::string& source,
                     const std::string& options) const;

  // The cache key text: device, driver, options and a hash of the source.
  static std::string key(const DeviceInfo& device, const std::string& source, const std::string& options);

  // Any backend's binaries: the entry stored under `key`, or nothing when the cache is off or the
  // entry is absent, damaged or of another key; store() never fails (a read-only or full cache
  // directory costs speed, not correctness).
  std::optional<std::string> load(const std::string& key) const;
  void store(const std::string& key, const std::string& binary) const;

 private:
  std::optional<std::filesystem::path> entry_file(const std::string& key) const;
  std::optional<std::filesystem::path> directory_;
};

}  // namespace cohort
