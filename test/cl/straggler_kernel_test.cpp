// Straggler rays through the OpenCL traversal (kernels/trace.cl on the default device, PoCL in CI):
// on adversarial rays the kernel visits exactly the nodes the host traversal visits, finds the same
// hits, and no ray visits a node whose cell it does not touch (test/accel/straggler_check.h).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "accel/straggler_check.h"
#include "runtime/bench/trace_bench.h"
#include "runtime/cl/context.h"
#include "runtime/cl/kernel_program.h"
#include "runtime/scene/scene.h"

namespace fs = std::filesystem;
using namespace cohort;
using namespace cohort::test;

namespace {

struct DeviceTrace {
  std::vector<HitOut> hits;
  std::vector<std::uint32_t> steps;
};

DeviceTrace trace_steps_on_device(const KdTree& tree, const std::vector<TestRay>& rays) {
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const ProgramBuild build = build_kernel_program(cl, cache, "trace.cl");
  std::vector<RayIn> in(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
    in[i] = RayIn{{rays[i].org.x, rays[i].org.y, rays[i].org.z, 0.f}, {rays[i].dir.x, rays[i].dir.y, rays[i].dir.z, INFINITY}};
  auto nodes = cl.buffer("nodes", tree.nodes.size() * sizeof(KdNode), tree.nodes.data());
  auto leaves = cl.buffer("leaves", tree.leaf_triangles.size() * 4, tree.leaf_triangles.data());
  auto tris = cl.buffer("triangles", tree.triangles.size() * sizeof(Triangle), tree.triangles.data());
  auto ray_buf = cl.buffer("rays", in.size() * sizeof(RayIn), in.data());
  auto hit_buf = cl.buffer("hits", in.size() * sizeof(HitOut));
  auto step_buf = cl.buffer("steps", in.size() * 4);
  cl::Kernel k(build.program, "trace_rays_steps");
  set_trace_rays_args(k, nodes, leaves, tris, tree.bounds, ray_buf, hit_buf, in.size(), false);
  k.setArg(9, step_buf);
  cl.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange((in.size() + 63) / 64 * 64), cl::NDRange(64));
  DeviceTrace out{std::vector<HitOut>(in.size()), std::vector<std::uint32_t>(in.size())};
  cl.queue.enqueueReadBuffer(hit_buf, CL_TRUE, 0, out.hits.size() * sizeof(HitOut), out.hits.data());
  cl.queue.enqueueReadBuffer(step_buf, CL_TRUE, 0, out.steps.size() * 4, out.steps.data());
  return out;
}

void expect_no_stragglers_on_device(const fs::path& path, std::size_t ray_count) {
  const KdTree tree = build_kdtree(load_scene(path).positions);
  const auto rays = straggler_rays(tree, ray_count, 777);
  const DeviceTrace device = trace_steps_on_device(tree, rays);
  const std::vector<std::uint32_t> host = host_visits(tree, rays);
  const KdTreeView view = view_of(tree);
  std::size_t step_differences = 0, hit_differences = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    step_differences += device.steps[i] != host[i];
    const TestRay& r = rays[i];
    const HitOut h = kd_trace(&view, v3(r.org.x, r.org.y, r.org.z), v3(r.dir.x, r.dir.y, r.dir.z), 0.f, INFINITY, 0);
    hit_differences += std::memcmp(&h, &device.hits[i], sizeof(HitOut)) != 0;
  }
  const StragglerCheck check = check_stragglers(tree, rays, device.steps);
  fmt::print("{}: {} rays, most nodes visited {}, 99.99th percentile {}, {} over the bound\n", path.filename().string(),
             check.rays, check.max_visited, check.p9999_visited, check.over_bound);
  for (const std::string& w : check.worst) fmt::print("  {}\n", w);
  EXPECT_EQ(check.over_bound, 0u);
  EXPECT_EQ(step_differences, 0u) << "the kernel and the host traversal visit different nodes";
  EXPECT_EQ(hit_differences, 0u) << "the kernel and the host traversal disagree on hits";
}

}  // namespace

TEST(StragglerKernel, ShippedCornellBox) {
  expect_no_stragglers_on_device(fs::path(COHORT_SOURCE_DIR) / "scenes/cornell-box.gltf", 60'000);
}

TEST(StragglerKernel, SharedBunny) {
  const fs::path bunny = fs::path(COHORT_SHARED_SCENES) / "bunny/bun_zipper_res2.ply";
  if (!fs::exists(bunny)) GTEST_SKIP() << "../shared/scenes is missing";
  expect_no_stragglers_on_device(bunny, 60'000);
}
