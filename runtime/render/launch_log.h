// Named kernel launches: every launch carries a name, and device time is summed per name, so
// `--stats` reads like the algorithm (as pbrt's ForAllQueued descriptions).
#pragma once

#include <CL/opencl.hpp>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runtime/cl/context.h"

namespace cohort {

class LaunchLog {
 public:
  // Enqueues `kernel` over `count` work items (rounded up to the work-group size). Nothing is
  // launched for count 0.
  void launch(const ClContext& cl, const cl::Kernel& kernel, const char* name, std::size_t count,
              std::size_t group = 64) {
    if (count == 0) return;
    cl::Event event;
    cl.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange((count + group - 1) / group * group),
                                  cl::NDRange(group), nullptr, &event);
    pending_.emplace_back(name, event);
  }

  // Device seconds per kernel name since the last call; waits for the launches to finish.
  std::map<std::string, double> collect() {
    std::map<std::string, double> seconds;
    for (auto& [name, event] : pending_) {
      event.wait();
      seconds[name] += event_seconds(event);
    }
    pending_.clear();
    return seconds;
  }

 private:
  std::vector<std::pair<const char*, cl::Event>> pending_;
};

inline void add_seconds(std::map<std::string, double>& into, const std::map<std::string, double>& from) {
  for (const auto& [name, s] : from) into[name] += s;
}

}  // namespace cohort
