// What build produced this binary, for benchmark reports. The commit is read at configure time
// (runtime/CMakeLists.txt); re-run cmake after committing for an exact figure.
#pragma once

namespace cohort {

struct BuildInfo {
  const char* git_commit;  // "unknown" outside a git checkout; "+dirty" when the tree had changes
  const char* build_type;
  const char* compiler;
  const char* cxx_flags;
};

BuildInfo build_info();

}  // namespace cohort
