// Where a device takes its sample passes and hands back their partial films: the one interface
// between a renderer's pass loop and whoever shares out the work (one device, several devices of
// this process, or MPI ranks).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/render/run/pass_schedule.h"

namespace cohort {

struct FilmState;

struct PassFilm {
  SamplePass pass;
  std::vector<co_float4> sums;  // per pixel: the pass's samples summed in sample order from zero;
                                // empty when the device added them to the image it keeps
  std::uint64_t dropped = 0;    // NaN or infinite samples of the pass
  std::uint64_t rays = 0;
  std::array<double, 3> totals{};  // with empty sums: the pass's sums added over the pixels
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

  // Non-null when this device alone renders every pass: the film the image starts from. The device
  // then keeps the image film itself, adds each pass to it in pass order (the float additions the
  // source would make, so the bits are the same) and delivers films with empty sums and totals
  // set: no partial film crosses to the host. `read_image` reads the image film on the calling
  // (device) thread, for checkpoints; the device calls deliver_image before it goes away.
  virtual const FilmState* device_keeps_image(std::function<std::vector<co_float4>()> read_image) {
    (void)read_image;
    return nullptr;
  }
  virtual void deliver_image(std::vector<co_float4> sums) { (void)sums; }
};

}  // namespace cohort
