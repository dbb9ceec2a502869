#include "runtime/cli/interrupt.h"

namespace cohort {
namespace {

volatile std::sig_atomic_t& received() {
  static volatile std::sig_atomic_t flag = 0;
  return flag;
}

extern "C" void on_stop_signal(int sig) { received() = sig; }

}  // namespace

InterruptGuard::InterruptGuard() {
  received() = 0;
  previous_int_ = std::signal(SIGINT, on_stop_signal);
  previous_term_ = std::signal(SIGTERM, on_stop_signal);
}

InterruptGuard::~InterruptGuard() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

bool InterruptGuard::requested() const { return received() != 0; }
int InterruptGuard::signal_number() const { return static_cast<int>(received()); }

}  // namespace cohort
