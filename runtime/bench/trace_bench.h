// Traversal alone: the protocol's rays traced by kernels/trace.cl (closest hit), timed by the
// kernel's profiling events, so upload, read-back and compilation are excluded.
#pragma once

#include <span>
#include <vector>

#include "runtime/accel/kdtree.h"
#include "runtime/bench/figures.h"
#include "runtime/bench/protocol_rays.h"
#include "runtime/cl/context.h"
#include "runtime/cl/program_cache.h"

namespace cohort {

// The arguments of kernels/trace.cl's trace_rays: the tree's buffers and bounds, count rays in,
// hits out, closest or any hit.
void set_trace_rays_args(cl::Kernel& kernel, const cl::Buffer& nodes, const cl::Buffer& leaf_triangles,
                         const cl::Buffer& triangles, const Bounds& bounds, const cl::Buffer& rays,
                         const cl::Buffer& hits, std::size_t count, bool any_hit);

class TraceBench {
 public:
  // The tree's buffers go to the device once; every trace() reuses them.
  TraceBench(const ClContext& cl, const ProgramCache& cache, const KdTree& tree);

  // Traces `rays` `reps` times (reps >= 1); hits come from the last repetition.
  TraceFigures trace(std::span<const RayIn> rays, unsigned reps, std::size_t group_size = 64) const;

  double compile_seconds() const { return compile_seconds_; }

 private:
  const ClContext& cl_;
  const KdTree& tree_;
  cl::Program program_;
  cl::Buffer nodes_, leaves_, triangles_;
  double compile_seconds_ = 0;
};

}  // namespace cohort
