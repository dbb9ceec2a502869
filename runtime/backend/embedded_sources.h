// Kernel sources embedded at build time (cmake/EmbedKernels.cmake), so the binary runs anywhere.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cohort {

struct EmbeddedSource {
  const char* path;  // relative to kernels/, e.g. "common/core/types.h" or "naive.cl"
  const char* text;
};

const std::vector<EmbeddedSource>& embedded_sources();

// The named .cl file with every `#include "..."` replaced by the embedded file, each file once;
// files are looked up in `first` (the tests' own kernels) before the production table.
// Throws std::runtime_error when a file is missing.
std::string expand_kernel_source(std::string_view path, const std::vector<EmbeddedSource>& first = {});

}  // namespace cohort
