// The protocol's rays (docs/bench-protocol.md) as `cohort bench` and the Embree harness generate them,
// and the traversal path of `cohort bench` that turns kernel hits into the protocol's triangle ids.
#include <gtest/gtest.h>

#include <cmath>

#include "runtime/bench/protocol_rays.h"
#include "runtime/bench/scene_bench.h"
#include "runtime/bench/trace_bench.h"
#include "runtime/backend/open_device.h"

using namespace cohort;

namespace {

glm::vec3 org_of(const RayIn& r) { return {r.origin.x, r.origin.y, r.origin.z}; }
glm::vec3 dir_of(const RayIn& r) { return {r.dir.x, r.dir.y, r.dir.z}; }

SceneCamera pinhole(glm::vec3 eye, glm::vec3 target, float vfov_degrees) {
  SceneCamera cam;
  cam.eye = eye;
  cam.target = target;
  cam.vfov_degrees = vfov_degrees;
  return cam;
}

}  // namespace

TEST(ProtocolRays, PcgMatchesTheProtocolFormula) {
  // values of the protocol's formula computed independently (Python, arbitrary precision masked to 32 bits)
  EXPECT_EQ(protocol_pcg(0u), 129708002u);
  EXPECT_EQ(protocol_pcg(1u), 2831084092u);
  EXPECT_EQ(protocol_pcg(3u), 2131687100u);
  EXPECT_EQ(protocol_pcg(12345u), 4099845390u);
  EXPECT_EQ(protocol_pcg(0xffffffffu), 3861530882u);
  EXPECT_EQ(protocol_unit(0xffffffffu), 16777215.f / 16777216.f);
  EXPECT_EQ(protocol_unit(0xffu), 0.f);  // the low 8 bits are dropped
}

TEST(ProtocolRays, PrimaryRaysThroughPixelCentresFromTheEye) {
  const SceneCamera cam = pinhole({1.f, 2.f, 10.f}, {1.f, 2.f, 0.f}, 45.f);
  const std::uint32_t res = 5;
  const auto rays = protocol_primary_rays(cam, res);
  ASSERT_EQ(rays.size(), 25u);
  for (const RayIn& r : rays) {
    EXPECT_EQ(org_of(r), cam.eye);
    EXPECT_EQ(r.origin.w, 0.f);
    EXPECT_TRUE(std::isinf(r.dir.w));
    EXPECT_NEAR(glm::length(dir_of(r)), 1.f, 1e-6f);
  }
  // the centre pixel looks at the target; pixel (0, 0) is top-left: up (+Y) and left (-X when looking -Z)
  const glm::vec3 centre = dir_of(rays[2 * res + 2]);
  EXPECT_NEAR(centre.z, -1.f, 1e-6f);
  const glm::vec3 top_left = dir_of(rays[0]);
  EXPECT_GT(top_left.y, 0.f);
  EXPECT_LT(top_left.x, 0.f);
  // its direction: px = py magnitudes (0.5/5*2 - 1 = -0.8) times tan(22.5 deg), normalised
  const float t = 0.8f * std::tan(glm::radians(22.5f));
  const glm::vec3 expected = glm::normalize(glm::vec3(-t, t, -1.f));
  EXPECT_NEAR(top_left.x, expected.x, 1e-6f);
  EXPECT_NEAR(top_left.y, expected.y, 1e-6f);
}

TEST(ProtocolRays, DiffuseRaysLeaveTheHitFacingTheIncomingRay) {
  // one triangle in z = 0; each winding gives a normal of opposite sign, the ray comes from +z
  for (const bool flip : {false, true}) {
    std::vector<glm::vec3> positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    if (flip) std::swap(positions[1], positions[2]);
    const float inf = INFINITY;
    std::vector<RayIn> primary;
    std::vector<ProtocolHit> hits;
    for (int i = 0; i < 64; ++i) {
      const float x = -0.3f + 0.01f * float(i);
      primary.push_back(RayIn{{x, 0.f, 2.f, 0.f}, {0.f, 0.f, -1.f, inf}});
      hits.push_back(i % 4 == 3 ? ProtocolHit{} : ProtocolHit{2.f, 0u});  // every 4th ray misses
    }
    const float diag = 3.f;
    const auto diffuse = protocol_diffuse_rays(primary, hits, positions, diag);
    ASSERT_EQ(diffuse.size(), 48u);
    std::size_t k = 0;
    for (std::size_t i = 0; i < primary.size(); ++i) {
      if (hits[i].triangle == HIT_NONE) continue;
      const RayIn& r = diffuse[k++];
      EXPECT_EQ(r.origin.x, primary[i].origin.x);
      EXPECT_FLOAT_EQ(r.origin.z, 1e-4f * diag);  // offset towards +z whatever the winding
      EXPECT_EQ(r.origin.w, 0.f);
      EXPECT_TRUE(std::isinf(r.dir.w));
      const glm::vec3 d = dir_of(r);
      EXPECT_NEAR(glm::length(d), 1.f, 1e-6f);
      // cosine-weighted: cos(theta) = sqrt(1 - u1) with u1 from pcg(2i + 1) of the pixel index
      const float u1 = protocol_unit(protocol_pcg(2u * std::uint32_t(i) + 1u));
      EXPECT_NEAR(d.z, std::sqrt(1.f - u1), 2e-6f);
    }
  }
}

TEST(ProtocolRays, DiffuseDirectionsAreCosineDistributed) {
  // the mean of cos(theta) over a cosine-weighted hemisphere is 2/3
  const std::vector<glm::vec3> positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  std::vector<RayIn> primary(20000, RayIn{{0.f, 0.f, 1.f, 0.f}, {0.f, 0.f, -1.f, INFINITY}});
  std::vector<ProtocolHit> hits(primary.size(), ProtocolHit{1.f, 0u});
  const auto diffuse = protocol_diffuse_rays(primary, hits, positions, 1.f);
  double sum = 0, sum_x = 0;
  for (const RayIn& r : diffuse) sum += r.dir.z, sum_x += r.dir.x;
  EXPECT_NEAR(sum / double(diffuse.size()), 2.0 / 3.0, 0.01);
  EXPECT_NEAR(sum_x / double(diffuse.size()), 0.0, 0.01);
}

// GPUs launch a pass's pixels in 8x4 tiles (tiled_pixel, kernels/common/core/types.h): every pixel
// exactly once for any image size, whole tiles where the image has room for them.
TEST(PixelOrder, TilesArePermutationsOfThePixelsForAnySize) {
  for (const auto& [w, h] : std::vector<std::pair<std::uint32_t, std::uint32_t>>{
           {1, 1}, {7, 3}, {8, 4}, {9, 5}, {13, 1}, {1, 13}, {16, 8}, {100, 37}, {256, 256}, {1023, 1025}}) {
    std::vector<int> seen(std::size_t(w) * h, 0);
    for (std::uint32_t k = 0; k < w * h; ++k) {
      const std::uint32_t pixel = tiled_pixel(k, w, h);
      ASSERT_LT(pixel, w * h) << w << "x" << h << " item " << k;
      ++seen[pixel];
    }
    for (std::size_t p = 0; p < seen.size(); ++p) ASSERT_EQ(seen[p], 1) << w << "x" << h << " pixel " << p;
  }
  // 32 consecutive items (a warp) are one 8x4 tile, tiles left to right, then the next band
  const std::uint32_t w = 24, h = 8;
  for (std::uint32_t k = 0; k < w * h; ++k) {
    const std::uint32_t tile = k / 32, x = tiled_pixel(k, w, h) % w, y = tiled_pixel(k, w, h) / w;
    EXPECT_EQ(x / 8, tile % 3) << k;
    EXPECT_EQ(y / 4, tile / 3) << k;
    EXPECT_EQ(x % 8 + 8 * (y % 4), k % 32) << k;  // a tile's pixels row by row
  }
  // a narrow last column of tiles and a short last band: 10x6 has tiles 8x4, 2x4, 8x2, 2x2
  EXPECT_EQ(tiled_pixel(31, 10, 6), 3u * 10u + 7u);
  EXPECT_EQ(tiled_pixel(32, 10, 6), 8u);
  EXPECT_EQ(tiled_pixel(39, 10, 6), 3u * 10u + 9u);
  EXPECT_EQ(tiled_pixel(40, 10, 6), 4u * 10u);
  EXPECT_EQ(tiled_pixel(56, 10, 6), 4u * 10u + 8u);
  EXPECT_EQ(tiled_pixel(59, 10, 6), 5u * 10u + 9u);
}

// The bench traces the protocol's rays in the device's launch order: the same rays, and each diffuse
// ray drawn from its own pixel's hash, whatever the order.
TEST(PixelOrder, TiledProtocolRaysAreTheRowOrdersRaysPermuted) {
  const SceneCamera cam = pinhole({0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, 50.f);
  const std::uint32_t res = 20;
  const auto rows = protocol_primary_rays(cam, res);
  const auto order = protocol_pixel_order(res, true);
  EXPECT_EQ(protocol_pixel_order(res, false)[57], 57u);
  const auto tiled = protocol_primary_rays(cam, res, order);
  ASSERT_EQ(tiled.size(), rows.size());
  const std::vector<glm::vec3> positions = {{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}};
  std::vector<ProtocolHit> row_hits(rows.size()), tiled_hits(rows.size());
  for (std::uint32_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(dir_of(tiled[k]), dir_of(rows[order[k]])) << k;
    // every third pixel misses; the hit lies on z = 0
    const std::uint32_t p = order[k];
    row_hits[p] = p % 3 == 0 ? ProtocolHit{} : ProtocolHit{3.f / -rows[p].dir.z, 0u};
    tiled_hits[k] = row_hits[p];
  }
  const auto row_diffuse = protocol_diffuse_rays(rows, row_hits, positions, 10.f);
  const auto tiled_diffuse = protocol_diffuse_rays(tiled, tiled_hits, positions, 10.f, order);
  ASSERT_EQ(tiled_diffuse.size(), row_diffuse.size());
  // the row order's diffuse rays in pixel order, matched to the tiled ones through their pixels
  std::vector<std::uint32_t> row_index(rows.size(), HIT_NONE);
  for (std::uint32_t p = 0, i = 0; p < rows.size(); ++p)
    if (row_hits[p].triangle != HIT_NONE) row_index[p] = i++;
  std::size_t j = 0;
  for (std::uint32_t k = 0; k < tiled.size(); ++k) {
    if (tiled_hits[k].triangle == HIT_NONE) continue;
    const RayIn& a = tiled_diffuse[j++];
    const RayIn& b = row_diffuse[row_index[order[k]]];
    EXPECT_EQ(org_of(a), org_of(b)) << k;
    EXPECT_EQ(dir_of(a), dir_of(b)) << k;
  }
}

TEST(ProtocolRays, ViewCamerasFollowTheProtocol) {
  Bounds b;
  b.extend(glm::vec3(0.f));
  b.extend(glm::vec3(2.f, 4.f, 4.f));
  const SceneCamera ext = view_camera(b, BenchView{});
  EXPECT_EQ(ext.eye, b.center() + glm::vec3(0.f, 0.f, b.diagonal()));
  EXPECT_EQ(ext.target, b.center());
  EXPECT_EQ(ext.vfov_degrees, 45.f);
  const SceneCamera in = view_camera(b, interior_view());
  EXPECT_EQ(in.eye, glm::vec3(0.5f, 0.8f, 2.f));
  EXPECT_EQ(in.target, glm::vec3(1.5f, 1.4f, 2.f));
  EXPECT_EQ(in.vfov_degrees, 60.f);
}

// The kernel path of `cohort bench` reports hits by Scene::positions index, as Embree's primID
// does, even when the KD-tree dropped a degenerate triangle before them (kept indices shift).
TEST(ProtocolRays, BenchTraceReportsSceneTriangleIndices) {
  Scene scene;
  scene.positions = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0},           // 0: degenerate, dropped by the builder
                     {-1, -1, 0}, {1, -1, 0}, {1, 1, 0},         // 1 and 2: a square in z = 0
                     {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0},
                     {-0.2f, -0.2f, 0.5f}, {0.2f, -0.2f, 0.5f}, {0.f, 0.2f, 0.5f}};  // 3: in front, z = 0.5
  const KdTree tree = build_kdtree(scene.positions);
  ASSERT_EQ(tree.stats.dropped_triangles, 1u);
  const Bounds bounds = scene.bounds();
  const auto device = open_device(Backend::opencl, "");
  const ProgramCache cache(ProgramCache::default_directory());
  const TraceBench bench(*device, cache, tree);
  const auto primary = protocol_primary_rays(view_camera(bounds, BenchView{}), 32);
  const TraceFigures f = bench.trace(primary, 3);
  EXPECT_EQ(f.rays_per_second.runs.size(), 3u);
  ASSERT_GT(f.hits, 100u);
  std::size_t front = 0;
  for (std::size_t i = 0; i < primary.size(); ++i) {
    const ProtocolHit& h = f.closest[i];
    if (h.triangle == HIT_NONE) continue;
    ASSERT_GE(h.triangle, 1u);
    ASSERT_LE(h.triangle, 3u);
    const glm::vec3 p = org_of(primary[i]) + h.t * dir_of(primary[i]);
    EXPECT_NEAR(p.z, h.triangle == 3 ? 0.5f : 0.f, 1e-5f);
    front += h.triangle == 3;
  }
  EXPECT_GT(front, 10u);
  const auto diffuse = protocol_diffuse_rays(primary, f.closest, scene.positions, bounds.diagonal());
  EXPECT_EQ(diffuse.size(), f.hits);
  for (const RayIn& r : diffuse) EXPECT_GT(r.dir.z, 0.f);  // every hit faces the camera at +z
}
