// What build produced this binary, for benchmark reports. The commit is read at every build
// (cmake/GitCommit.cmake), so it names the commit the binary was built from.
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
