// The OpenCL traversal kernel (kernels/trace.cl on the default device, PoCL in CI) against a
// brute-force loop over every triangle on the host (culled by bounding spheres, re-checked without
// the culling on every 50th ray): >= 100k rays on three scenes.
#include <gtest/gtest.h>

#include <array>
#include <atomic>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <span>

#include <tbb/parallel_for.h>

#include "accel/ray_check.h"
#include "host/scene_paths.h"
#include "kernels/test_kernels.h"
#include "runtime/bench/trace_bench.h"
#include "runtime/cl/cl_error.h"
#include "runtime/cl/context.h"
#include "runtime/cl/kernel_program.h"
#include "runtime/render/scene/device_scene.h"
#include "runtime/scene/scene.h"

namespace fs = std::filesystem;
using namespace cohort;
using namespace cohort::test;

namespace {

// With `bvh`, through that BVH (the program built with COHORT_ACCEL_BVH4, COHORT_ACCEL_BVH8 or
// COHORT_ACCEL_BVH8F), else
// the KD-tree.
std::vector<HitOut> trace_on_device(const KdTree& tree, const std::vector<TestRay>& rays, bool any_hit,
                                    const std::vector<float>& tmax, WideBvh bvh = {}) {
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  // the arrays and build option a render would use (traversal_arrays)
  const TraversalArrays arrays = traversal_arrays(tree, bvh);
  const DeviceProgram program = cl.build_program(cache, "trace", arrays.build_option);
  std::vector<RayIn> in(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
    in[i] = RayIn{{rays[i].org.x, rays[i].org.y, rays[i].org.z, 0.f}, {rays[i].dir.x, rays[i].dir.y, rays[i].dir.z, tmax[i]}};
  const DeviceBuffer nodes = cl.allocate("nodes", arrays.node_bytes, arrays.nodes);
  const DeviceBuffer leaves = cl.allocate("leaves", arrays.leaf_list_bytes, arrays.leaf_lists);
  const DeviceBuffer tris = cl.allocate("triangles", tree.triangles.size() * sizeof(Triangle), tree.triangles.data());
  const DeviceBuffer ray_buf = cl.allocate("rays", in.size() * sizeof(RayIn), in.data());
  const DeviceBuffer hit_buf = cl.allocate("hits", in.size() * sizeof(HitOut));
  DeviceKernel k = program.kernel("trace_rays");
  set_trace_rays_args(k, nodes, leaves, tris, tree.bounds, ray_buf, hit_buf, in.size(), any_hit);
  cl.launch(k, in.size(), 64);
  std::vector<HitOut> hits(in.size());
  cl.read(hit_buf, 0, hits.size() * sizeof(HitOut), hits.data());
  return hits;
}

float triangle_t(const KdTree& tree, const TestRay& ray, std::uint32_t tri) {
  const WatertightRay wr = watertight_ray(v3(ray.org.x, ray.org.y, ray.org.z), v3(ray.dir.x, ray.dir.y, ray.dir.z));
  const Triangle& t = tree.triangles[tri];
  float th = INFINITY, u, v;
  intersect_triangle(&wr, v3_from4(t.v0), v3_from4(t.v1), v3_from4(t.v2), 0.f, INFINITY, &th, &u, &v);
  return th;
}

void check_scene(const fs::path& path, std::size_t ray_count) {
  const Scene scene = load_scene(path);
  const KdTree tree = build_kdtree(scene.positions);
  const auto rays = make_rays(tree.bounds, ray_count, 1234);
  const std::vector<float> unbounded(rays.size(), INFINITY);
  const auto closest = trace_on_device(tree, rays, false, unbounded);
  std::vector<HitOut> expected(rays.size());
  std::vector<float> half(rays.size()), beyond(rays.size());
  // every triangle, less those whose bounding sphere the ray misses, every 50th ray re-checked
  // through the plain loop (ray_check.h), as check_against_brute_force does
  const SphereCulledBruteForce brute(tree);
  std::atomic<std::size_t> culling_errors{0};
  tbb::parallel_for(std::size_t(0), rays.size(), [&](std::size_t i) {
    const RecheckedHit rechecked = brute.closest_rechecked(rays[i], i);
    expected[i] = rechecked.hit;
    if (!rechecked.culling_ok) ++culling_errors;
  });
  EXPECT_EQ(culling_errors.load(), 0u) << "the culled brute force missed a hit of the plain one";
  std::size_t hits = 0, ties = 0, mismatches = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const HitOut& e = expected[i];
    const HitOut& g = closest[i];
    half[i] = e.triangle == HIT_NONE ? INFINITY : 0.5f * e.t;
    beyond[i] = e.triangle == HIT_NONE ? INFINITY : 1.5f * e.t;
    if ((e.triangle == HIT_NONE) != (g.triangle == HIT_NONE)) { ++mismatches; continue; }
    if (e.triangle == HIT_NONE) continue;
    ++hits;
    if (std::abs(g.t - e.t) > 1e-5f * std::abs(e.t)) {
      if (mismatches < 5) std::printf("mismatch: brute tri %u t %.9g, kernel tri %u t %.9g\n", e.triangle, e.t, g.triangle, g.t);
      ++mismatches;
      continue;
    }
    if (g.triangle != e.triangle) {
      // a different triangle counts only at a genuine tie: its own t equals the closest t exactly
      if (triangle_t(tree, rays[i], g.triangle) == e.t) ++ties;
      else {
        if (mismatches < 5)
          std::printf("mismatch: brute tri %u t %.9g, kernel tri %u t %.9g (own t %.9g)\n", e.triangle, e.t, g.triangle,
                      g.t, triangle_t(tree, rays[i], g.triangle));
        ++mismatches;
      }
    }
  }
  // any hit: nothing before half the closest distance, something before 1.5 times it
  const auto occluded_half = trace_on_device(tree, rays, true, half);
  const auto occluded_beyond = trace_on_device(tree, rays, true, beyond);
  std::size_t occlusion_mismatches = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const bool hit = expected[i].triangle != HIT_NONE;
    if (occluded_half[i].triangle != HIT_NONE) ++occlusion_mismatches;
    if (hit != (occluded_beyond[i].triangle != HIT_NONE)) ++occlusion_mismatches;
  }
  std::printf("%s: %zu rays, %zu hits, %zu ties, %zu mismatches, %zu any-hit mismatches\n",
              path.filename().c_str(), rays.size(), hits, ties, mismatches, occlusion_mismatches);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(occlusion_mismatches, 0u);
  EXPECT_GT(hits, rays.size() / 10);  // the rays must actually exercise the tree
}

// The BVH kernel (4- or 8-wide, compressed or with float planes: `Bvh` and its builder) on the device against the KD-tree kernel, bit
// for bit (t, u, v, triangle), on rays aimed at shared vertices and edges and random ones, closest
// and any hit: what lets a CPU trace the BVH and render the GPU's image.
template <class Bvh>
void check_bvh_against_kd(const fs::path& path, Bvh (*build)(std::span<const Triangle>)) {
  const Scene scene = load_scene(path);
  const KdTree tree = build_kdtree(scene.positions);
  const Bvh bvh = build(tree.triangles);
  auto rays = make_feature_rays(tree, 20000, 99);
  const auto random = make_rays(tree.bounds, 20000, 98);
  rays.insert(rays.end(), random.begin(), random.end());
  // origins that are not finite: no hit on either tree, and the walk stays inside the BVH
  const float nan = std::nanf("");
  for (const auto& [x, y, z] : {std::array{nan, 0.f, 0.f}, std::array{nan, nan, nan}, std::array{INFINITY, 0.f, -INFINITY}}) {
    auto ray = rays[7];
    ray.org = glm::vec3(x, y, z);
    rays.push_back(ray);
  }
  const std::vector<float> unbounded(rays.size(), INFINITY);
  const auto kd = trace_on_device(tree, rays, false, unbounded);
  const auto through_bvh = trace_on_device(tree, rays, false, unbounded, &bvh);
  std::vector<float> half(rays.size());
  std::size_t hits = 0, differ = 0, occlusion_differ = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    hits += kd[i].triangle != HIT_NONE;
    differ += std::memcmp(&kd[i], &through_bvh[i], sizeof(HitOut)) != 0;
    half[i] = kd[i].triangle == HIT_NONE ? INFINITY : 0.5f * kd[i].t;
  }
  const auto kd_occluded = trace_on_device(tree, rays, true, half);
  const auto bvh_occluded = trace_on_device(tree, rays, true, half, &bvh);
  for (std::size_t i = 0; i < rays.size(); ++i)
    occlusion_differ += (kd_occluded[i].triangle != HIT_NONE) != (bvh_occluded[i].triangle != HIT_NONE);
  for (std::size_t i = rays.size() - 3; i < rays.size(); ++i) EXPECT_EQ(through_bvh[i].triangle, HIT_NONE) << "ray " << i;
  std::printf("%s: %zu rays, %zu hits, %zu closest and %zu any-hit answers differ between the KD-tree and the BVH\n",
              path.filename().c_str(), rays.size(), hits, differ, occlusion_differ);
  EXPECT_GT(hits, rays.size() / 4);
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(occlusion_differ, 0u);
}

}  // namespace

TEST(TraceKernel, Bvh4GivesTheKdTreesHitsOnTheCornellBox) {
  check_bvh_against_kd(fs::path(COHORT_SOURCE_DIR) / "scenes/cornell-box.gltf", build_bvh4);
}

TEST(TraceKernel, Bvh8GivesTheKdTreesHitsOnTheCornellBox) {
  check_bvh_against_kd(fs::path(COHORT_SOURCE_DIR) / "scenes/cornell-box.gltf", build_bvh8);
}

TEST(TraceKernel, Bvh8GivesTheKdTreesHitsOnTheVoxelTerrain) {
  check_bvh_against_kd(fs::path(COHORT_SOURCE_DIR) / "scenes/voxel-terrain.gltf", build_bvh8);
}

// The 8-wide BVH with float planes: its float8 box tests (one AVX operation per plane row on an AVX
// CPU) give every lane the 4-wide test's answer.
TEST(TraceKernel, Bvh8fGivesTheKdTreesHitsOnTheCornellBox) {
  check_bvh_against_kd(fs::path(COHORT_SOURCE_DIR) / "scenes/cornell-box.gltf", build_bvh8f);
}

TEST(TraceKernel, Bvh8fGivesTheKdTreesHitsOnTheVoxelTerrain) {
  check_bvh_against_kd(fs::path(COHORT_SOURCE_DIR) / "scenes/voxel-terrain.gltf", build_bvh8f);
}

TEST(TraceKernel, Bvh8fGivesTheKdTreesHitsOnTheBunny) {
  if (!fs::exists(shared("bunny"))) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  check_bvh_against_kd(shared("bunny/bun_zipper_res2.ply"), build_bvh8f);
}

TEST(TraceKernel, Bvh4GivesTheKdTreesHitsOnTheBunny) {
  if (!fs::exists(shared("bunny"))) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  check_bvh_against_kd(shared("bunny/bun_zipper_res2.ply"), build_bvh4);
}

TEST(TraceKernel, Bvh8GivesTheKdTreesHitsOnTheBunny) {
  if (!fs::exists(shared("bunny"))) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  check_bvh_against_kd(shared("bunny/bun_zipper_res2.ply"), build_bvh8);
}

TEST(TraceKernel, CornellBoxMatchesBruteForce) {
  check_scene(fs::path(COHORT_SOURCE_DIR) / "scenes/cornell-box.gltf", 100000);
}

TEST(TraceKernel, BunnyMatchesBruteForce) {
  if (!fs::exists(shared("bunny"))) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  check_scene(shared("bunny/bun_zipper_res2.ply"), 100000);
}

TEST(TraceKernel, CornellSphereMatchesBruteForce) {
  if (!fs::exists(shared("cornell-box-mcguire"))) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  check_scene(shared("cornell-box-mcguire/CornellBox-Sphere.obj"), 100000);
}

// co_c8_count, which counts each ray's visits in bvh8f_trace_packet (the naive kernel's camera
// packets), as the device compiles it: OpenCL's int8, where a true comparison is -1 in each lane.
TEST(PortHelpers, EightLaneCountsAddOneToTheLanesOfEachMask) {
  std::unique_ptr<ClContext> cl;
  ProgramBuild build;
  try {
    cl = std::make_unique<ClContext>(select_device(""));
    build = build_test_kernel_program(*cl, ProgramCache(ProgramCache::default_directory()), "port_test.cl");
  } catch (const std::exception& ex) {
    GTEST_SKIP() << "no OpenCL device: " << ex.what();
  }
  std::vector<cl_uint> masks;
  for (cl_uint m = 0; m < 256; ++m) masks.push_back(m);
  for (cl_uint l = 0; l < 8; ++l)  // lane l alone, l + 1 times: each lane's count its own
    for (cl_uint i = 0; i <= l; ++i) masks.push_back(1u << l);
  std::array<int, 8> expected{};
  for (const cl_uint m : masks)
    for (int l = 0; l < 8; ++l) expected[l] += (m >> l) & 1u;
  auto mask_buf = cl->buffer("masks", masks.size() * 4, masks.data());
  auto out_buf = cl->buffer("counts", 8 * 4);
  cl::Kernel k(build.program, "count8_test");
  k.setArg(0, mask_buf);
  k.setArg(1, cl_uint(masks.size()));
  k.setArg(2, out_buf);
  cl->queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(1));
  std::array<int, 8> counted{};
  cl->queue.enqueueReadBuffer(out_buf, CL_TRUE, 0, 8 * 4, counted.data());
  EXPECT_EQ(counted, expected);
  EXPECT_EQ(expected[7] - expected[0], 7);  // the masks tell the lanes apart
}
