// Where the shipped scenes and the external models (scenes/external.json) are. The GPU machine runs test binaries built
// elsewhere: $COHORT_SOURCE_DIR and $COHORT_SHARED_SCENES, when set, override the build's paths.
#pragma once

#include <cstdlib>
#include <filesystem>

namespace cohort::test {

inline std::filesystem::path env_or(const char* var, const char* built_in) {
  const char* v = std::getenv(var);
  return v && *v ? std::filesystem::path(v) : std::filesystem::path(built_in);
}

inline std::filesystem::path shipped(const char* name) {
  return env_or("COHORT_SOURCE_DIR", COHORT_SOURCE_DIR) / "scenes" / name;
}

inline std::filesystem::path shared(const char* rel) {
  return env_or("COHORT_SHARED_SCENES", COHORT_SHARED_SCENES) / rel;
}

}  // namespace cohort::test
