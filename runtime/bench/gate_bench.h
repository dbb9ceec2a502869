// The gate experiment of the coherence issue, as a benchmark anyone can rerun on their device and
// scene: how fast does the plain traversal kernel trace one bounce's rays in each order, and what
// would a device sort of that order's keys cost? Bounce 1 is the protocol's primary rays; bounce
// k + 1 the protocol's diffuse rays from bounce k's hits (misses leave the wave, as compaction does).
// Orders are computed on the host; hits are the same in every order (checked).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/bench/figures.h"
#include "runtime/backend/device.h"
#include "runtime/backend/program_cache.h"
#include "runtime/render/scene/prepared_scene.h"

namespace cohort {

struct GateOrder {
  std::string name;  // generation, origin-first, direction-first, paper, pth-32, two-point (exact distance),
                     // two-point-estimate (the render's estimate), random
  unsigned key_bits = 0;         // 0: no key (generation order)
  RateFigure rays_per_second;    // trace_rays over the rays in this order
  double sort_ms = 0;            // device radix sort of `rays` keys of key_bits (median), with the values
};

struct GateBounce {
  unsigned bounce = 1;
  std::size_t rays = 0;
  std::vector<GateOrder> orders;
  bool hits_agree = true;  // every order found the same hits as generation order
};

struct GateOptions {
  std::uint32_t res = 1024;  // res x res primary rays: the wave size of bounce 1
  unsigned bounces = 3;
  unsigned reps = 3;
};

std::vector<GateBounce> gate_bench(const Device& device, const ProgramCache& cache, const PreparedScene& scene,
                                   const SceneCamera& camera, const GateOptions& options);

}  // namespace cohort
