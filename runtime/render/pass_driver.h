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

// Renders samples [params.sample_offset, + params.samples_per_pass) of every pixel of the pass
// (pass_pixel_count: all, or params.active_pixels of buffers.pixel_list) into the film,
// and waits for its launches before it returns (the parameters are written without blocking).
// (One launch of a pass: a pass may take several.)
using PassFunction = std::function<PassOutput(const PassBuffers&, const RenderParams&)>;

// max_samples_per_pass bounds what one launch may hold (a method's per-launch buffers). `cache`
// builds the film program when this device keeps the image film (PassSource::device_keeps_image).
RenderResult drive_passes(const Device& cl, const ProgramCache& cache, const RenderParams& params,
                          const RenderSettings& settings,
                          std::uint32_t max_samples_per_pass, const ProgressCallback& progress,
                          const RenderControl& control, const PassFunction& pass);

}  // namespace cohort
