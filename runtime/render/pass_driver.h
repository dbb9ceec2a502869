// The loop every method shares: passes of samples over the whole image until the sample count
// or the time limit is reached, a film that each pass adds to in sample order, progress, and the
// final image.
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
  DeviceBuffer film;     // float4 per pixel: the running sum of samples
  DeviceBuffer dropped;  // uint: NaN or infinite samples
};

struct PassOutput {
  std::uint64_t rays = 0;
  std::map<std::string, double> kernel_seconds;
};

// Renders samples [params.sample_offset, + params.samples_per_pass) of every pixel into the film.
using PassFunction = std::function<PassOutput(const PassBuffers&, const RenderParams&)>;

// max_samples_per_pass bounds what one pass may hold (a method's per-pass buffers).
RenderResult drive_passes(const Device& cl, const RenderParams& params, const RenderSettings& settings,
                          std::uint32_t max_samples_per_pass, const ProgressCallback& progress,
                          const RenderControl& control, const PassFunction& pass);

}  // namespace cohort
