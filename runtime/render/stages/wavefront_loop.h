// The loop every wavefront method shares: a pool of path slots (path_pool.h), the wavefront program,
// and for each sample pass a loop of bounces until no path is live and no work item is left. A
// method says what one bounce runs, as a sequence of the stages in stages.h and sorted_traversal.h.
// Queue lengths stay on the device (launches cover the pool, work items past the count leave), and
// each bounce's figures go to a row on the device: the host reads the counters and rows only every
// few bounces, to learn whether the pass is over, and keeps the per-bounce figures of --stats.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "runtime/backend/kernel_args.h"
#include "runtime/render/launch_log.h"
#include "runtime/render/methods/method.h"
#include "runtime/render/pass_driver.h"
#include "runtime/render/stages/path_pool.h"

namespace cohort {

// Which slots a launch covers: every slot of the pool, or with stream compaction (Wald 2011) only
// the queue of live slots that wf_finish compacts after every bounce.
enum class Launches { all_slots, compacted };

struct WavefrontKernels {
  DeviceKernel generate, extend, shade, shadow, finish, accumulate, simd_efficiency, shadow_max_steps, end_bounce;
};

// One sample pass in flight: what the stages of a bounce share.
struct WavefrontPass {
  const Device& device;
  const RenderSettings& settings;
  PathPool& pool;
  WavefrontKernels& kernels;
  const SceneBuffers& scene;
  const PassBuffers& buffers;
  const DeviceBuffer& results;  // one radiance per work item of the pass
  Launches launches;
  LaunchLog log;  // this bounce's launches, timed when the host next reads the device
  PassOutput out;
  std::uint32_t items = 0;   // work items (pixel, sample) of the pass
  std::uint32_t bounce = 0;  // the bounce being enqueued, from 0 in each pass
  bool items_left = true;    // false once a read of the counters showed every item handed out
  // At least the paths in flight: the pool, until a read shows that no new path can start; from
  // then on the live count that read found (it can only fall).
  std::uint32_t live_bound = 0;

  std::uint32_t use_queue() const { return launches == Launches::compacted ? 1u : 0u; }
  // work items of a launch over the paths: the worst case (with the queue, the kernels take the
  // live count from the device and the rest leave at once); without the queue, every slot
  std::uint32_t count() const { return launches == Launches::compacted ? live_bound : pool.slots; }
};

// A method's bounce: enqueues its stages. The loop, not the method, decides when the pass is over.
using BounceStages = std::function<void(WavefrontPass&)>;

class WavefrontRender {
 public:
  WavefrontRender(const MethodInputs& in, Launches launches);

  const MethodInputs& inputs() const { return in_; }
  const PathPool& pool() const { return pool_; }
  RenderResult run(const BounceStages& bounce);

 private:
  const MethodInputs& in_;
  Launches launches_;
  DeviceProgram program_;
  std::uint32_t pixels_ = 0, max_per_pass_ = 0;
  PathPool pool_;
  DeviceBuffer results_;
  WavefrontKernels kernels_;
  SceneBuffers scene_;
};

}  // namespace cohort
