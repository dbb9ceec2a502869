// The partial traversal in local memory followed by the resumed traversal (kernels/trace.cl,
// trace_rays_pth, on PoCL) against the full traversal, and its PTH bits against an independent
// geometric walk on the host.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "accel/ray_check.h"
#include "host/scene_paths.h"
#include "runtime/cl/context.h"
#include "runtime/cl/kernel_program.h"
#include "runtime/render/scene/device_scene.h"
#include "runtime/scene/scene.h"

namespace fs = std::filesystem;
using namespace cohort;
using namespace cohort::test;

namespace {

struct DeviceTrace {
  std::vector<HitOut> hits;
  std::vector<std::uint32_t> bits;
};

enum class Traversal { full, partial, speculative };

// Full traversal, partial + resumed traversal (with subtree_nodes and levels), or full traversal
// with speculative leaf tests (the nodes each ray visits in `bits`).
DeviceTrace trace(const KdTree& tree, const std::vector<TestRay>& rays, std::uint32_t subtree_nodes,
                  std::uint32_t levels, Traversal mode) {
  const bool partial = mode == Traversal::partial;
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
  auto bit_buf = cl.buffer("bits", in.size() * 4);
  const co_float4 lo{tree.bounds.lo.x, tree.bounds.lo.y, tree.bounds.lo.z, 0.f};
  const co_float4 hi{tree.bounds.hi.x, tree.bounds.hi.y, tree.bounds.hi.z, 0.f};
  const char* name = partial                           ? "trace_rays_pth"
                     : mode == Traversal::speculative ? "trace_rays_speculative"
                                                      : "trace_rays";
  cl::Kernel k(build.program, name);
  cl_uint a = 0;
  k.setArg(a++, nodes);
  k.setArg(a++, leaves);
  k.setArg(a++, tris);
  k.setArg(a++, sizeof(lo), &lo);
  k.setArg(a++, sizeof(hi), &hi);
  k.setArg(a++, ray_buf);
  k.setArg(a++, hit_buf);
  k.setArg(a++, static_cast<cl_uint>(in.size()));
  if (partial) {
    k.setArg(a++, cl::Local(std::max<std::size_t>(subtree_nodes, 1) * sizeof(KdNode)));
    k.setArg(a++, subtree_nodes);
    k.setArg(a++, levels);
    k.setArg(a++, bit_buf);
  } else if (mode == Traversal::speculative) {
    k.setArg(a++, bit_buf);  // nodes visited per ray
  } else {
    k.setArg(a++, cl_uint(0));
  }
  k.setArg(a++, cl_uint(0));  // co_params_end (kernels/common/core/kernel_params.h)
  // the speculative kernel votes per work-group: one SIMD group of 32 where the kernel allows it;
  // the renderers' sizes (Device::launch) within the kernel's limit on this device
  const std::size_t group = cl_launch_group(k, cl.cl_device, mode == Traversal::speculative ? 32 : 0);
  cl.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange((in.size() + group - 1) / group * group),
                                cl::NDRange(group));
  DeviceTrace out;
  out.hits.resize(in.size());
  out.bits.resize(in.size());
  cl.queue.enqueueReadBuffer(hit_buf, CL_TRUE, 0, out.hits.size() * sizeof(HitOut), out.hits.data());
  if (mode != Traversal::full) cl.queue.enqueueReadBuffer(bit_buf, CL_TRUE, 0, out.bits.size() * 4, out.bits.data());
  return out;
}

// Independent reference: walks the first descent with node boxes and slab tests (no split-plane
// distances), recording per level (went left, both children entered). `margin` receives how close
// the decision at any level came to flipping, relative to the interval; the device widens its
// decisions by 4e-6 relative, so only rays within that margin may legitimately differ.
std::uint32_t reference_bits(const KdTree& tree, const TestRay& ray, std::uint32_t levels, double& margin) {
  margin = INFINITY;
  auto clip = [&](const Bounds& b, double& t0, double& t1) {
    t0 = 0;
    t1 = INFINITY;
    for (int a = 0; a < 3; ++a) {
      const double o = ray.org[a], inv = 1.0 / double(ray.dir[a]);
      double n = (b.lo[a] - o) * inv, f = (b.hi[a] - o) * inv;
      if (n > f) std::swap(n, f);
      if (!std::isnan(n)) t0 = std::max(t0, n);
      if (!std::isnan(f)) t1 = std::min(t1, f);
    }
    return t0 <= t1;
  };
  Bounds box = tree.bounds;
  double t0, t1;
  if (!clip(box, t0, t1)) return 0;
  std::uint32_t node = 0, bits = 0, level = 0;
  for (; level < levels; ++level) {
    const KdNode n = tree.nodes[node];
    if (kd_is_leaf(n)) break;
    const int axis = static_cast<int>(kd_axis(n));
    const float split = co_as_float(n.word1);
    Bounds left = box, right = box;
    left.hi[axis] = split;
    right.lo[axis] = split;
    double l0, l1, r0, r1;
    const bool in_left = clip(left, l0, l1) && l1 >= t0 && l0 <= t1;
    const bool in_right = clip(right, r0, r1) && r1 >= t0 && r0 <= t1;
    const double plane_t = (split - ray.org[axis]) / double(ray.dir[axis]);
    const double scale = std::max(std::abs(plane_t), std::abs(t1));
    if (std::isfinite(plane_t))
      margin = std::min({margin, std::abs(plane_t - t0) / scale, std::abs(plane_t - t1) / scale});
    bool go_left;
    if (in_left && in_right) go_left = ray.org[axis] < split || (ray.org[axis] == split && ray.dir[axis] <= 0);
    else go_left = in_left;
    bits = (bits << 2) | (go_left ? 2u : 0u) | (in_left && in_right ? 1u : 0u);
    node = kd_left_child(n) + (go_left ? 0 : 1);
    box = go_left ? left : right;
    clip(box, t0, t1);
  }
  return levels ? bits << (2 * (levels - level)) : 0;
}

void check(const fs::path& path, std::uint32_t levels) {
  const Scene scene = load_scene(path);
  const KdTree tree = build_kdtree(scene.positions);
  const SceneTables tables = make_scene_tables(scene, tree);
  DeviceScene facts;  // only for the level table
  const ClContext cl(select_device(""));
  facts = upload_scene(cl, tree, tables);
  const std::uint32_t tree_levels = static_cast<std::uint32_t>(facts.level_starts.size() - 1);
  const std::uint32_t walk = std::min(levels, tree_levels);
  const std::uint32_t subtree = facts.level_starts[walk];
  const auto rays = make_rays(tree.bounds, 100000, 4321);
  const DeviceTrace full = trace(tree, rays, 0, 0, Traversal::full);
  const DeviceTrace partial = trace(tree, rays, subtree, walk, Traversal::partial);
  const DeviceTrace speculative = trace(tree, rays, 0, 0, Traversal::speculative);
  std::size_t hit_mismatch = 0, speculative_mismatch = 0, bit_mismatch = 0, bit_mismatch_outside_margin = 0, hits = 0;
  std::uint64_t speculative_steps = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (std::memcmp(&full.hits[i], &partial.hits[i], sizeof(HitOut)) != 0) ++hit_mismatch;
    if (std::memcmp(&full.hits[i], &speculative.hits[i], sizeof(HitOut)) != 0) ++speculative_mismatch;
    speculative_steps += speculative.bits[i];
    hits += full.hits[i].triangle != HIT_NONE;
    double margin = 0;
    const std::uint32_t expected = reference_bits(tree, rays[i], walk, margin);
    if (expected != partial.bits[i]) {
      ++bit_mismatch;
      if (margin > 1e-5) ++bit_mismatch_outside_margin;
    }
  }
  std::printf("%s: %u of %u tree levels walked (%u subtree nodes); %zu rays, %zu hits; %zu hit differences; "
              "PTH bits differ from the reference on %zu rays (%zu beyond the widening margin); speculative "
              "traversal: %zu hit differences, %.1f nodes per ray\n",
              path.filename().c_str(), walk, tree_levels, subtree, rays.size(), hits, hit_mismatch, bit_mismatch,
              bit_mismatch_outside_margin, speculative_mismatch, double(speculative_steps) / double(rays.size()));
  EXPECT_EQ(hit_mismatch, 0u);
  EXPECT_EQ(speculative_mismatch, 0u);
  EXPECT_GE(speculative_steps, hits);  // the kernel did walk the tree: a hit takes at least a leaf
  EXPECT_EQ(bit_mismatch_outside_margin, 0u);
  EXPECT_LE(bit_mismatch, rays.size() / 10000);
  EXPECT_GT(hits, rays.size() / 10);
}


}  // namespace

TEST(PthKernel, CornellBoxResumeEqualsFullTraversal) { check(shipped("cornell-box.gltf"), 10); }

TEST(PthKernel, TreeShallowerThanTheSubtree) {
  // one triangle: the whole tree is one leaf; the quad-light scene: a few levels only
  check(shipped("single-triangle.gltf"), 10);
  check(shipped("quad-light.obj"), 16);
}

TEST(PthKernel, BunnyResumeEqualsFullTraversal) {
  if (!fs::exists(shared("bunny"))) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  check(shared("bunny/bun_zipper_res2.ply"), 10);
}

TEST(PthKernel, SponzaDeepSubtree) {
  if (!fs::exists(shared("dabrovic-sponza"))) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  check(shared("dabrovic-sponza/sponza.obj.gz"), 14);
}
