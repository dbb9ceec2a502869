// Runs the traversal-only kernels (kernels/common/wavefront/trace_kernels.h) on any backend: the full
// traversal (trace_rays) or the PTH walk in local memory followed by the resumed traversal
// (trace_rays_pth), for the same rays on every device.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/backend/device.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/backend/program_cache.h"

namespace cohort::test {

struct TraceOutput {
  std::vector<HitOut> hits;
  std::vector<std::uint32_t> pth_bits;  // partial traversal only
};

// levels = 0: full traversal; otherwise the walk covers `subtree_nodes` nodes over `levels` levels.
inline TraceOutput trace_on_device(const Device& device, const ProgramCache& cache, const KdTree& tree,
                                   const std::vector<RayIn>& rays, std::uint32_t subtree_nodes, std::uint32_t levels) {
  const DeviceProgram program = device.build_program(cache, "trace");
  const bool partial = levels > 0;
  DeviceKernel k = program.kernel(partial ? "trace_rays_pth" : "trace_rays");
  const auto count = static_cast<std::uint32_t>(rays.size());
  TraceTree t;
  t.nodes = device.allocate("nodes", tree.nodes.size() * sizeof(KdNode), tree.nodes.data());
  t.leaf_triangles = device.allocate("leaves", tree.leaf_triangles.size() * 4, tree.leaf_triangles.data());
  t.triangles = device.allocate("triangles", tree.triangles.size() * sizeof(Triangle), tree.triangles.data());
  t.scene_min = co_float4{tree.bounds.lo.x, tree.bounds.lo.y, tree.bounds.lo.z, 0.f};
  t.scene_max = co_float4{tree.bounds.hi.x, tree.bounds.hi.y, tree.bounds.hi.z, 0.f};
  const DeviceBuffer ray_buf = device.allocate("rays", rays.size() * sizeof(RayIn), rays.data());
  const DeviceBuffer hit_buf = device.allocate("hits", rays.size() * sizeof(HitOut));
  const DeviceBuffer bit_buf = device.allocate("bits", rays.size() * 4);
  if (partial) {
    TraceRaysPthArgs args;
    args.tree = t;
    args.rays = ray_buf;
    args.hits = hit_buf;
    args.count = count;
    args.subtree = LocalMemory{std::max<std::size_t>(subtree_nodes, 1) * sizeof(KdNode)};
    args.subtree_nodes = subtree_nodes;
    args.levels = levels;
    args.pth_bits = bit_buf;
    args.bind(k);
  } else {
    TraceRaysArgs args;
    args.tree = t;
    args.rays = ray_buf;
    args.hits = hit_buf;
    args.count = count;
    args.bind(k);
  }
  device.launch(k, rays.size(), 64);
  TraceOutput out;
  out.hits.resize(rays.size());
  device.read(hit_buf, 0, out.hits.size() * sizeof(HitOut), out.hits.data());
  if (partial) {
    out.pth_bits.resize(rays.size());
    device.read(bit_buf, 0, out.pth_bits.size() * 4, out.pth_bits.data());
  }
  return out;
}

// Rays of the traversal tests (test/accel/ray_check.h's make_rays) as kernel input, tmin 0, tmax inf.
template <class TestRays>
std::vector<RayIn> ray_inputs(const TestRays& rays) {
  std::vector<RayIn> in;
  in.reserve(rays.size());
  for (const auto& r : rays)
    in.push_back(RayIn{{r.org.x, r.org.y, r.org.z, 0.f}, {r.dir.x, r.dir.y, r.dir.z, INFINITY}});
  return in;
}

}  // namespace cohort::test
