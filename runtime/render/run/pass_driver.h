// The loop every method shares: takes sample passes (pass_schedule.h) from control.passes, or
// from a job of its own when it renders the image alone, renders each into a film zeroed for the
// pass (in launches of growing size, each adding in sample order) and hands the partial film back.
// With a job of its own it returns the image; with shared passes, only this device's figures.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "runtime/backend/device.h"
#include "runtime/render/renderer.h"

namespace cohort {

struct PassBuffers {
  DeviceBuffer params;   // RenderParams, sample_offset and samples_per_pass set for this pass
  DeviceBuffer film;     // float4 per pixel: the running sum of the pass's samples
  DeviceBuffer dropped;  // uint: NaN or infinite samples
  DeviceBuffer pixel_list;  // uint per pixel: an adaptive pass's pixels (RenderParams::active_pixels)
};

struct PassOutput {
  std::uint64_t rays = 0;
  std::map<std::string, double> kernel_seconds;
  std::uint32_t max_steps = 0;  // the most KD-tree nodes one ray visited
  std::uint32_t host_reads = 0;     // blocking reads of device memory inside the launch
  std::uint32_t sort_launches = 0;  // device commands the ray sorts issued
  // with RenderSettings::straggler_rays: nodes visited by every extension ray, and the worst rays
  std::vector<std::uint32_t> extension_steps;
  std::vector<StragglerRay> worst_rays;
};

// Keeps the `keep` rays that visited the most nodes (ties: the earlier), the most first.
void keep_worst(std::vector<StragglerRay>& worst, std::vector<StragglerRay> more, std::size_t keep);

// One method set up on one device (programs built, buffers allocated): what a launch of a sample
// pass runs, and the method's own figures once the passes are done.
class PassLauncher {
 public:
  virtual ~PassLauncher() = default;
  // The most samples of a pass one launch may hold (the method's per-launch buffers).
  virtual std::uint32_t max_samples_per_launch() const = 0;
  // The first launch's samples: launches then grow (by doubling) while they are short.
  virtual std::uint32_t first_launch_samples() const { return 1; }
  // Renders samples [params.sample_offset, + params.samples_per_pass) of every pixel of the pass
  // (pass_pixel_count: all, or params.active_pixels of buffers.pixel_list), adding them in sample
  // order to buffers.film, and waits for its launches before it returns (the parameters are
  // written without blocking). Launch sizes do not change the image: the film is a running sum.
  virtual PassOutput launch(const PassBuffers& buffers, const RenderParams& params) = 0;
  // The method's figures (compile time, per-bounce statistics, its settings) into the result.
  virtual void report(RenderResult& result) const = 0;
};

// Drives the passes through `launcher`'s launches, then adds its report. `cache` builds the film
// program when this device keeps the image film (PassSource::device_keeps_image).
RenderResult drive_passes(const Device& cl, const ProgramCache& cache, const RenderParams& params,
                          const RenderSettings& settings, const ProgressCallback& progress,
                          const RenderControl& control, PassLauncher& launcher);

}  // namespace cohort
