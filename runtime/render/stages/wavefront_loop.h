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
#include <memory>
#include <string>
#include <vector>

#include "runtime/backend/kernel_args.h"
#include "runtime/render/run/launch_log.h"
#include "runtime/render/methods/method.h"
#include "runtime/render/run/pass_driver.h"
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

// What every wavefront method allocates alike: the pool and one radiance per work item of a
// launch. Sized for the render (not the method), so the methods auto probes share one.
struct WavefrontMemory {
  std::uint32_t max_per_launch = 0;  // samples per pixel one launch holds
  PathPool pool;
  DeviceBuffer results;

  WavefrontMemory(const Device& device, const RenderSettings& settings);
};

class WavefrontRender final : public PassLauncher {
 public:
  WavefrontRender(const MethodInputs& in, Launches launches);

  // What one bounce runs, and the figures the method adds to the loop's (e.g. its sort's).
  void set_bounce(BounceStages bounce, std::function<void(RenderResult&)> report = {});

  const MethodInputs& inputs() const { return in_; }
  const PathPool& pool() const { return memory_->pool; }

  std::uint32_t max_samples_per_launch() const override { return memory_->max_per_launch; }
  PassOutput launch(const PassBuffers& buffers, const RenderParams& params) override;
  void report(RenderResult& result) const override;

 private:
  MethodInputs in_;
  Launches launches_;
  DeviceProgram program_;
  std::shared_ptr<WavefrontMemory> memory_;
  WavefrontKernels kernels_;
  SceneBuffers scene_;
  BounceStages bounce_;
  std::function<void(RenderResult&)> report_;
  std::vector<IterationStats> iterations_;
};

}  // namespace cohort
