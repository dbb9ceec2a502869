// The loop every wavefront method shares: a pool of path slots (path_pool.h), the wavefront program,
// and for each sample pass a loop of bounces until no path is live and no work item is left. A
// method says what one bounce runs, as a sequence of the stages in stages.h and ray_sort.h; the loop
// reads the queue counters after each bounce and keeps the per-bounce figures of --stats.
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
  DeviceKernel generate, extend, shade, shadow, finish, accumulate, simd_efficiency, shadow_max_steps;
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
  LaunchLog log;
  PassOutput out;
  std::map<std::string, double> sort_seconds;  // device time of the radix sort's launches
  std::uint32_t items = 0;                     // work items (pixel, sample) of the pass
  std::uint64_t remaining = 0;                 // work items no path has taken yet
  std::uint32_t live = 0;                      // paths in flight
  std::uint32_t bounce = 0;                    // 1 for the pass's first bounce (its camera rays)

  std::uint32_t use_queue() const { return launches == Launches::compacted ? 1u : 0u; }
  // work items of a launch over the paths: the live ones, or every slot
  std::uint32_t count() const { return launches == Launches::compacted ? live : pool.slots; }
};

// A method's bounce: runs its stages; false when no path is live after it started new ones.
using BounceStages = std::function<bool(WavefrontPass&)>;

class WavefrontRender {
 public:
  // `sort_bytes_per_slot`: what a ray-sorting stage adds to each slot (SORT_SLOT_BYTES), 0 without.
  WavefrontRender(const MethodInputs& in, Launches launches, std::size_t sort_bytes_per_slot = 0);

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
