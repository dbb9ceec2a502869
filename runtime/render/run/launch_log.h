// Named kernel launches: every launch carries a name, and device time is summed per name, so
// `--stats` reads like the algorithm (as pbrt's ForAllQueued descriptions).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runtime/backend/device.h"

namespace cohort {

class LaunchLog {
 public:
  // Enqueues `kernel` over `count` work items (rounded up to the work-group size; `group` as
  // Device::launch: 0 is the kernel's own size). Nothing is launched for count 0.
  void launch(const Device& device, const DeviceKernel& kernel, const char* name, std::size_t count,
              std::size_t group = 0) {
    if (count == 0) return;
    pending_.emplace_back(name, device.launch(kernel, count, group));
  }

  // A launch made elsewhere (the radix sort's), timed with the others.
  void add(const char* name, DeviceEvent event) { pending_.emplace_back(name, std::move(event)); }

  // Device seconds per kernel name since the last call; waits for the launches to finish.
  std::map<std::string, double> collect() {
    std::map<std::string, double> seconds;
    for (auto& [name, event] : pending_) {
      seconds[name] += event.seconds();
    }
    pending_.clear();
    return seconds;
  }

 private:
  std::vector<std::pair<const char*, DeviceEvent>> pending_;
};

inline void add_seconds(std::map<std::string, double>& into, const std::map<std::string, double>& from) {
  for (const auto& [name, s] : from) into[name] += s;
}

}  // namespace cohort
