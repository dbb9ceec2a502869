// Straggler rays through the OpenCL traversal (kernels/trace.cl, trace_rays_steps, on the default
// device): on rays built to straggle (test/accel/straggler_check.h) the kernel visits exactly the
// nodes the host traversal visits, finds the same hits, and no ray visits a node whose cell it does
// not touch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "accel/ray_check.h"
#include "accel/straggler_check.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/backend/program_cache.h"
#include "runtime/cl/context.h"
#include "runtime/scene/scene.h"

namespace fs = std::filesystem;
using namespace cohort;
using namespace cohort::test;

namespace {

// The nodes each ray visits in the kernel's full traversal of the KD-tree, and its hits (as
// host_visits gives the host traversal's).
std::vector<std::uint32_t> device_visits(const KdTree& tree, const std::vector<TestRay>& rays,
                                         std::vector<HitOut>* hits) {
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceProgram program = cl.build_program(cache, "trace");
  std::vector<RayIn> in(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
    in[i] = RayIn{{rays[i].org.x, rays[i].org.y, rays[i].org.z, 0.f}, {rays[i].dir.x, rays[i].dir.y, rays[i].dir.z, INFINITY}};
  TraceRaysStepsArgs args;
  args.tree.nodes = cl.allocate("nodes", tree.nodes.size() * sizeof(KdNode), tree.nodes.data());
  args.tree.leaf_triangles = cl.allocate("leaves", tree.leaf_triangles.size() * 4, tree.leaf_triangles.data());
  args.tree.triangles = cl.allocate("triangles", tree.triangles.size() * sizeof(Triangle), tree.triangles.data());
  args.tree.scene_min = {tree.bounds.lo.x, tree.bounds.lo.y, tree.bounds.lo.z, 0.f};
  args.tree.scene_max = {tree.bounds.hi.x, tree.bounds.hi.y, tree.bounds.hi.z, 0.f};
  args.rays = cl.allocate("rays", in.size() * sizeof(RayIn), in.data());
  args.hits = cl.allocate("hits", in.size() * sizeof(HitOut));
  args.count = static_cast<std::uint32_t>(in.size());
  args.any_hit = 0;
  args.steps = cl.allocate("steps", in.size() * 4);
  DeviceKernel k = program.kernel("trace_rays_steps");
  args.bind(k);
  cl.launch(k, in.size());  // the renderers' work-group size within the kernel's limit
  hits->resize(in.size());
  cl.read(args.hits, 0, hits->size() * sizeof(HitOut), hits->data());
  std::vector<std::uint32_t> steps(in.size());
  cl.read(args.steps, 0, steps.size() * 4, steps.data());
  return steps;
}

void expect_no_stragglers_on_device(const fs::path& path, std::size_t ray_count) {
  const KdTree tree = build_kdtree(load_scene(path).positions);
  const auto rays = straggler_rays(tree, ray_count, 777);
  std::vector<HitOut> device_hits, host_hits;
  const std::vector<std::uint32_t> device = device_visits(tree, rays, &device_hits);
  const std::vector<std::uint32_t> host = host_visits(tree, rays, &host_hits);
  std::size_t step_differences = 0, hit_differences = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    step_differences += device[i] != host[i];
    hit_differences += std::memcmp(&host_hits[i], &device_hits[i], sizeof(HitOut)) != 0;
  }
  const StragglerCheck check = check_stragglers(tree, rays, device);
  std::printf("%s: %zu rays, most nodes visited %u, 99.99th percentile %u, %zu over the bound\n",
              path.filename().c_str(), check.rays, check.max_visited, check.p9999_visited, check.over_bound);
  for (const std::string& w : check.worst) std::printf("  %s\n", w.c_str());
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
  if (!fs::exists(bunny)) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  expect_no_stragglers_on_device(bunny, 60'000);
}
