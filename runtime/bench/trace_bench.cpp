#include "runtime/bench/trace_bench.h"

#include <fmt/format.h>

#include <algorithm>

#include "runtime/backend/kernel_args.h"
#include "runtime/render/scene/device_scene.h"

namespace cohort {

void set_trace_rays_args(DeviceKernel& k, const DeviceBuffer& nodes, const DeviceBuffer& leaf_triangles,
                         const DeviceBuffer& triangles, const Bounds& bounds, const DeviceBuffer& rays,
                         const DeviceBuffer& hits, std::size_t count, bool any_hit) {
  const co_float4 lo{bounds.lo.x, bounds.lo.y, bounds.lo.z, 0.f};
  const co_float4 hi{bounds.hi.x, bounds.hi.y, bounds.hi.z, 0.f};
  TraceRaysArgs args;
  args.tree.nodes = nodes;
  args.tree.leaf_triangles = leaf_triangles;
  args.tree.triangles = triangles;
  args.tree.scene_min = lo;
  args.tree.scene_max = hi;
  args.rays = rays;
  args.hits = hits;
  args.count = static_cast<std::uint32_t>(count);
  args.any_hit = static_cast<std::uint32_t>(any_hit);
  args.bind(k);
}

TraceBench::TraceBench(const Device& device, const ProgramCache& cache, const KdTree& tree, WideBvh bvh)
    : device_(device), tree_(tree) {
  const TraversalArrays arrays = traversal_arrays(tree, bvh);
  program_ = device.build_program(cache, "trace", arrays.build_option);
  compile_seconds_ = program_.seconds;
  nodes_ = device.allocate(fmt::format("{} nodes", arrays.name), arrays.node_bytes, arrays.nodes, Access::read_only);
  leaves_ = device.allocate("leaf lists", arrays.leaf_list_bytes, arrays.leaf_lists, Access::read_only);
  triangles_ = device.allocate("triangles", tree.triangles.size() * sizeof(Triangle), tree.triangles.data(),
                               Access::read_only);
}

TraceFigures TraceBench::trace(std::span<const RayIn> rays, unsigned reps, std::size_t group_size) const {
  TraceFigures f;
  f.rays = rays.size();
  f.closest.assign(rays.size(), ProtocolHit{});
  if (rays.empty()) return f;
  const DeviceBuffer ray_buf =
      device_.allocate("rays", rays.size() * sizeof(RayIn), rays.data(), Access::read_only);
  const DeviceBuffer hit_buf = device_.allocate("hits", rays.size() * sizeof(HitOut));
  DeviceKernel k = program_.kernel("trace_rays");
  set_trace_rays_args(k, nodes_, leaves_, triangles_, tree_.bounds, ray_buf, hit_buf, rays.size(), false);
  for (unsigned r = 0; r < std::max(reps, 1u); ++r) {
    const double s = device_.launch(k, rays.size(), group_size).seconds();
    f.rays_per_second.runs.push_back(s > 0 ? double(rays.size()) / s : 0.0);
  }
  std::vector<HitOut> hits(rays.size());
  device_.read(hit_buf, 0, hits.size() * sizeof(HitOut), hits.data());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (hits[i].triangle == HIT_NONE) continue;
    ++f.hits;
    f.closest[i] = ProtocolHit{hits[i].t, tree_.source_index[hits[i].triangle]};
  }
  return f;
}

}  // namespace cohort
