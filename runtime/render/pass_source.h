// Where a device takes its sample passes and hands back their partial films: the one interface
// between a renderer's pass loop and whoever shares out the work (one device, several devices of
// this process, or MPI ranks).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "kernels/common/types.h"
#include "runtime/render/pass_schedule.h"

namespace cohort {

struct PassFilm {
  SamplePass pass;
  std::vector<co_float4> sums;  // per pixel: the pass's samples summed in sample order from zero
  std::uint64_t dropped = 0;    // NaN or infinite samples of the pass
  std::uint64_t rays = 0;
};

class PassSource {
 public:
  virtual ~PassSource() = default;
  // The device has its scene and programs and is about to ask for passes.
  virtual void device_ready() {}
  // Blocks until a pass may start; nullopt when this device is done.
  virtual std::optional<SamplePass> next() = 0;
  virtual void deliver(PassFilm film) = 0;
  // A device failed: hand out nothing more and wake every waiter, so the others stop too.
  virtual void abort() = 0;
};

}  // namespace cohort
