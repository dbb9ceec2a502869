// SIGINT and SIGTERM stop a render after its current pass instead of killing it, so the image
// so far and a checkpoint are saved. Signal handlers can only talk through a static flag: this
// is the one piece of global state, and the guard restores the previous handlers.
#pragma once

#include <csignal>

namespace cohort {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  bool requested() const;
  int signal_number() const;  // the signal that asked to stop, 0 if none

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

}  // namespace cohort
