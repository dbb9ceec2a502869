// Traversal alone: the protocol's rays traced by kernels/trace.cl (closest hit), timed by the
// kernel's device events, so upload, read-back and compilation are excluded.
#pragma once

#include <span>
#include <vector>

#include "runtime/accel/wide_bvh.h"
#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/bench/figures.h"
#include "runtime/bench/protocol_rays.h"
#include "runtime/backend/device.h"
#include "runtime/backend/program_cache.h"

namespace cohort {

// The arguments of kernels/trace.cl's trace_rays: the tree's buffers and bounds, count rays in,
// hits out, closest or any hit.
void set_trace_rays_args(DeviceKernel& kernel, const DeviceBuffer& nodes, const DeviceBuffer& leaf_triangles,
                         const DeviceBuffer& triangles, const Bounds& bounds, const DeviceBuffer& rays,
                         const DeviceBuffer& hits, std::size_t count, bool any_hit);

class TraceBench {
 public:
  // The tree's buffers go to the device once; every trace() reuses them.
  // With `bvh`, the rays trace through it (the KD-tree then gives the kept triangles only).
  TraceBench(const Device& device, const ProgramCache& cache, const KdTree& tree, WideBvh bvh = {});

  // Traces `rays` `reps` times (reps >= 1); hits come from the last repetition.
  TraceFigures trace(std::span<const RayIn> rays, unsigned reps, std::size_t group_size = 0) const;

  double compile_seconds() const { return compile_seconds_; }

 private:
  const Device& device_;
  const KdTree& tree_;
  DeviceProgram program_;
  DeviceBuffer nodes_, leaves_, triangles_;
  double compile_seconds_ = 0;
};

}  // namespace cohort
