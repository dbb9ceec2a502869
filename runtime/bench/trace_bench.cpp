#include "runtime/bench/trace_bench.h"

#include "runtime/cl/kernel_program.h"

namespace cohort {

void set_trace_rays_args(cl::Kernel& k, const cl::Buffer& nodes, const cl::Buffer& leaf_triangles,
                         const cl::Buffer& triangles, const Bounds& bounds, const cl::Buffer& rays,
                         const cl::Buffer& hits, std::size_t count, bool any_hit) {
  const co_float4 lo{bounds.lo.x, bounds.lo.y, bounds.lo.z, 0.f};
  const co_float4 hi{bounds.hi.x, bounds.hi.y, bounds.hi.z, 0.f};
  k.setArg(0, nodes);
  k.setArg(1, leaf_triangles);
  k.setArg(2, triangles);
  k.setArg(3, sizeof(lo), &lo);
  k.setArg(4, sizeof(hi), &hi);
  k.setArg(5, rays);
  k.setArg(6, hits);
  k.setArg(7, static_cast<cl_uint>(count));
  k.setArg(8, static_cast<cl_uint>(any_hit));
}

TraceBench::TraceBench(const ClContext& cl, const ProgramCache& cache, const KdTree& tree) : cl_(cl), tree_(tree) {
  const ProgramBuild build = build_kernel_program(cl, cache, "trace.cl");
  program_ = build.program;
  compile_seconds_ = build.seconds;
  nodes_ = cl.buffer("kd-tree nodes", tree.nodes.size() * sizeof(KdNode), tree.nodes.data(), CL_MEM_READ_ONLY);
  leaves_ = cl.buffer("leaf lists", tree.leaf_triangles.size() * 4, tree.leaf_triangles.data(), CL_MEM_READ_ONLY);
  triangles_ = cl.buffer("triangles", tree.triangles.size() * sizeof(Triangle), tree.triangles.data(),
                         CL_MEM_READ_ONLY);
}

TraceFigures TraceBench::trace(std::span<const RayIn> rays, unsigned reps, std::size_t group_size) const {
  TraceFigures f;
  f.rays = rays.size();
  f.closest.assign(rays.size(), ProtocolHit{});
  if (rays.empty()) return f;
  auto ray_buf = cl_.buffer("rays", rays.size() * sizeof(RayIn), rays.data(), CL_MEM_READ_ONLY);
  auto hit_buf = cl_.buffer("hits", rays.size() * sizeof(HitOut));
  cl::Kernel k(program_, "trace_rays");
  set_trace_rays_args(k, nodes_, leaves_, triangles_, tree_.bounds, ray_buf, hit_buf, rays.size(), false);
  const std::size_t global = (rays.size() + group_size - 1) / group_size * group_size;
  for (unsigned r = 0; r < std::max(reps, 1u); ++r) {
    cl::Event event;
    cl_.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), cl::NDRange(group_size), nullptr, &event);
    event.wait();
    const double s = event_seconds(event);
    f.rays_per_second.runs.push_back(s > 0 ? double(rays.size()) / s : 0.0);
  }
  std::vector<HitOut> hits(rays.size());
  cl_.queue.enqueueReadBuffer(hit_buf, CL_TRUE, 0, hits.size() * sizeof(HitOut), hits.data());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (hits[i].triangle == HIT_NONE) continue;
    ++f.hits;
    f.closest[i] = ProtocolHit{hits[i].t, tree_.source_index[hits[i].triangle]};
  }
  return f;
}

}  // namespace cohort
