// Repeated measurements of a rate (median and best, as the protocol reports them) and of a workload.
#pragma once

#include <algorithm>
#include <vector>

#include "runtime/bench/protocol_rays.h"
#include "runtime/util/median.h"

namespace cohort {

struct RateFigure {
  std::vector<double> runs;  // one rate per repetition

  double median() const { return cohort::median(runs); }
  double best() const { return runs.empty() ? 0 : *std::max_element(runs.begin(), runs.end()); }
};

// One traversal workload (protocol rays), traced reps times.
struct TraceFigures {
  std::size_t rays = 0;
  std::size_t hits = 0;
  RateFigure rays_per_second;
  std::vector<ProtocolHit> closest;  // per ray; triangles as indices into Scene::positions / 3
};

}  // namespace cohort
