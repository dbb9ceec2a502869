// The shared kernels compiled as host C++ (HostDevice) against the same kernels compiled as OpenCL C
// on the default device (PoCL in CI): traversal, PTH walk and resume, the radix sort and every
// rendering method must agree bit for bit. CUDA compiles the same headers as C++ with the same
// rounding, so a divergence that only a C++ compiler produces shows up here, without a GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <random>

#include "accel/ray_check.h"
#include "host/host_device.h"
#include "host/scene_paths.h"
#include "host/trace_on_device.h"
#include "runtime/cl/context.h"
#include "runtime/render/scene/prepared_scene.h"
#include "runtime/render/methods/methods.h"
#include "runtime/sort/radix_sort.h"

namespace fs = std::filesystem;
using namespace cohort;
using namespace cohort::test;

namespace {

const ProgramCache& cache() {
  static const ProgramCache c(ProgramCache::default_directory());
  return c;
}

const ClContext& opencl() {
  static const ClContext cl(select_device(""));
  return cl;
}

template <class T>
std::size_t count_differences(const std::vector<T>& a, const std::vector<T>& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
  return n;
}

void check_traversal(const fs::path& path, std::uint32_t levels) {
  const PreparedScene p = prepare_scene(path);
  const HostDevice host;
  const DeviceScene facts = upload_scene(host, p.tree, p.tables);  // for the level table only
  const std::uint32_t walk = std::min<std::uint32_t>(levels, static_cast<std::uint32_t>(facts.level_starts.size() - 1));
  const std::uint32_t subtree = facts.level_starts[walk];
  const auto rays = ray_inputs(make_rays(p.tree.bounds, 20000, 99));
  const TraceOutput host_full = trace_on_device(host, cache(), p.tree, rays, 0, 0);
  const TraceOutput cl_full = trace_on_device(opencl(), cache(), p.tree, rays, 0, 0);
  const TraceOutput host_pth = trace_on_device(host, cache(), p.tree, rays, subtree, walk);
  const TraceOutput cl_pth = trace_on_device(opencl(), cache(), p.tree, rays, subtree, walk);
  std::size_t hits = 0;
  for (const auto& h : cl_full.hits) hits += h.triangle != HIT_NONE;
  EXPECT_GT(hits, rays.size() / 10) << "too few hits to prove anything";
  EXPECT_EQ(count_differences(host_full.hits, cl_full.hits), 0u) << path << ": full traversal";
  EXPECT_EQ(count_differences(host_pth.hits, cl_pth.hits), 0u) << path << ": PTH walk + resume";
  EXPECT_EQ(count_differences(host_pth.pth_bits, cl_pth.pth_bits), 0u) << path << ": PTH bits";
  EXPECT_EQ(count_differences(host_pth.hits, host_full.hits), 0u) << path << ": resume equals full traversal";
}

}  // namespace

TEST(HostKernels, TraversalAndPthWalkEqualOpenCl) {
  check_traversal(shipped("cornell-box.gltf"), 10);
  check_traversal(shipped("quad-light.obj"), 16);
  const fs::path bunny = shared("bunny/bun_zipper_res2.ply");
  if (fs::exists(bunny)) check_traversal(bunny, 10);
}

TEST(HostKernels, RadixSortEqualsOpenClAndStableSort) {
  std::mt19937_64 rng(5);
  const std::uint32_t n = 70000;  // 18 tiles of 4096: look-back across tiles
  std::vector<std::uint64_t> keys(n);
  for (auto& k : keys) k = rng() & 0xfffffffffull;  // 36 bits: 6 passes of 6 bits
  for (std::uint32_t i = 0; i < n; i += 7) keys[i] = keys[i / 2];  // duplicates: stability matters
  const std::vector<std::uint32_t> keys32(keys.begin(), keys.end());  // the low 32 bits: 4 passes of 8
  std::vector<std::uint32_t> values(n);
  std::iota(values.begin(), values.end(), 0u);
  auto run = [&](const Device& device, SortKey key) {
    RadixSort sort(device, cache(), n, key);
    const bool wide = key == SortKey::bits64;
    const DeviceBuffer k = wide ? device.allocate("keys", n * 8ull, keys.data())
                                : device.allocate("keys", n * 4ull, keys32.data());
    const DeviceBuffer v = device.allocate("values", n * 4ull, values.data());
    sort.sort(k, v, n, wide ? 36 : 32);
    std::vector<std::uint32_t> out(n);
    device.read(v, 0, n * 4ull, out.data());
    return out;
  };
  std::vector<std::uint32_t> want = values, want32 = values;
  std::stable_sort(want.begin(), want.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  std::stable_sort(want32.begin(), want32.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return keys32[a] < keys32[b]; });
  const HostDevice host;
  EXPECT_EQ(run(host, SortKey::bits64), want);
  EXPECT_EQ(run(opencl(), SortKey::bits64), want);
  EXPECT_EQ(run(host, SortKey::bits32), want32);
  EXPECT_EQ(run(opencl(), SortKey::bits32), want32);
}

TEST(HostKernels, EveryMethodRendersTheOpenClImage) {
  const PreparedScene p = prepare_scene(shipped("cornell-box.gltf"));
  const HostDevice host;
  const DeviceScene host_scene = upload_scene(host, p.tree, p.tables);
  const DeviceScene cl_scene = upload_scene(opencl(), p.tree, p.tables);
  RenderSettings s;
  s.width = 20;
  s.height = 16;
  s.spp = 2;
  s.max_depth = 6;
  for (const auto& name : method_names()) {
    s.method = name;
    const RenderResult a = render(host, cache(), host_scene, p.camera, s);
    const RenderResult b = render(opencl(), cache(), cl_scene, p.camera, s);
    ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
    EXPECT_EQ(count_differences(a.image.rgb, b.image.rgb), 0u) << name;
    EXPECT_EQ(a.rays, b.rays) << name;
    double sum = 0;
    for (float v : b.image.rgb) sum += v;
    EXPECT_GT(sum, 0.0) << name << ": a black image proves nothing";
  }
}
