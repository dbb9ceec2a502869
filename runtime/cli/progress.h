// Progress on stderr: a bar redrawn in place on a terminal, plain lines otherwise (logs, CI).
#pragma once

#include <cstdio>

#include "runtime/render/renderer.h"

namespace cohort {

class ProgressReporter {
 public:
  explicit ProgressReporter(std::FILE* out);
  void update(const Progress& p);
  void finish();

 private:
  std::FILE* out_;
  bool terminal_;
  double last_line_ = -1;  // seconds of the last plain line
  bool drawn_ = false;
};

}  // namespace cohort
