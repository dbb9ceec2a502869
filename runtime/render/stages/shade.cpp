#include "runtime/render/stages/stages.h"

namespace cohort {

void shade(WavefrontPass& p) {
  const std::uint32_t count = p.count();
  WfShadeArgs args;
  args.params = p.buffers.params;
  args.scene = p.scene;
  args.path = p.pool.path;
  args.hits = p.pool.hits;
  args.queue = p.pool.queue;
  args.use_queue = p.use_queue();
  args.count = count;
  args.shadow = p.pool.shadow;
  args.counters = p.pool.counters;
  args.pixel_list = p.buffers.pixel_list;
  args.bind(p.kernels.shade);
  p.log.launch(p.device, p.kernels.shade, "shade", count);

  WfShadowArgs shadow;
  shadow.params = p.buffers.params;
  shadow.scene = p.scene;
  shadow.path_radiance = p.pool.path.path_radiance;
  shadow.shadow = p.pool.shadow;
  shadow.counters = p.pool.counters;
  shadow.steps = p.pool.steps;
  shadow.bind(p.kernels.shadow);
  // at most one shadow ray per live path; the kernel reads how many were queued
  p.log.launch(p.device, p.kernels.shadow, "shadow", p.live_bound);

  WfShadowMaxStepsArgs max_steps;
  max_steps.steps = p.pool.steps;
  max_steps.counters = p.pool.counters;
  max_steps.bind(p.kernels.shadow_max_steps);
  p.log.launch(p.device, p.kernels.shadow_max_steps, "simd efficiency", (p.live_bound + SIMD_GROUP - 1) / SIMD_GROUP);
}

}  // namespace cohort
