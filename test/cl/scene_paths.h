// Where the kernel tests find their scenes: the project's own (scenes/) and ../shared/scenes.
#pragma once

#include <filesystem>

namespace cohort::cl_test {

inline std::filesystem::path shipped(const char* name) {
  return std::filesystem::path(COHORT_SOURCE_DIR) / "scenes" / name;
}
inline std::filesystem::path shared(const char* rel) { return std::filesystem::path(COHORT_SHARED_SCENES) / rel; }

}  // namespace cohort::cl_test
