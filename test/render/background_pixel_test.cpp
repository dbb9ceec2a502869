// camera_pixel_misses_box (kernels/common/shading/camera.h), which lets the CPU's naive kernel give a
// pixel of the background its sky without a camera ray per sample: it must never claim a pixel through
// which a ray meets the box, and it must claim most of those that no ray comes near.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/common/shading/camera.h"
#include "runtime/render/scene/camera_params.h"

using namespace cohort;

namespace {

// Whether the ray from `eye` along `d` meets the box, in double, the box grown by 1e-6 of its size.
bool meets_box(const co_vec3& eye, const co_vec3& d, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 pad = 1e-6 * (hi - lo);
  const double o[3] = {eye.x, eye.y, eye.z}, v[3] = {d.x, d.y, d.z};
  double t0 = 0.0, t1 = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const double l = lo[a] - pad[a], h = hi[a] + pad[a];
    if (v[a] == 0.0) {
      if (o[a] < l || o[a] > h) return false;
      continue;
    }
    double ta = (l - o[a]) / v[a], tb = (h - o[a]) / v[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

// Random cameras, half of them mirrored, and boxes (in front, beside, behind, around the eye, some a
// few pixels wide): every pixel the test claims is missed by the rays of a 7x7 grid of jitters
// through it (its edges and corners among them), and among the pixels whose grid rays all miss,
// most are claimed.
TEST(CameraPixels, ClaimsOnlyPixelsWhoseRaysMissTheBox) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const int width = 24, height = 18, grid = 7;
  int claimed = 0, missed_everywhere = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SceneCamera camera;
    camera.eye = 10.0f * glm::vec3(u(rng), u(rng), u(rng));
    camera.target = camera.eye + glm::vec3(u(rng), u(rng), u(rng));
    camera.vfov_degrees = 20.0f + 60.0f * (0.5f + 0.5f * u(rng));
    CameraParams cam = make_camera_params(camera, width, height);
    if (trial % 2) cam.right = co_make_float4(-cam.right.x, -cam.right.y, -cam.right.z, 0.0f);  // a mirrored frame
    const glm::vec3 centre = trial % 5 == 0 ? camera.eye + 0.5f * glm::vec3(u(rng), u(rng), u(rng))
                                            : 12.0f * glm::vec3(u(rng), u(rng), u(rng));
    const glm::vec3 half = (trial % 3 == 0 ? 0.05f : 3.0f) * glm::abs(glm::vec3(u(rng), u(rng), u(rng))) + 1e-3f;
    const glm::vec3 lo = centre - half, hi = centre + half;
    const co_vec3 eye = v3(cam.eye.x, cam.eye.y, cam.eye.z);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        bool any = false;
        for (int j = 0; j < grid * grid; ++j) {
          const float jx = std::min(float(j % grid) / (grid - 1), 0.99999994f);
          const float jy = std::min(float(j / grid) / (grid - 1), 0.99999994f);
          any |= meets_box(eye, camera_direction(&cam, width, height, x, y, jx, jy), lo, hi);
        }
        const int claim = camera_pixel_misses_box(&cam, width, height, x, y, v3(lo.x, lo.y, lo.z), v3(hi.x, hi.y, hi.z));
        ASSERT_FALSE(claim && any) << "trial " << trial << " pixel " << x << "," << y;
        claimed += claim;
        missed_everywhere += !any;
      }
  }
  EXPECT_GT(missed_everywhere, 20'000);
  EXPECT_GT(claimed, missed_everywhere * 8 / 10);  // the planes separate most of what misses
}

// A pixel whose corner ray passes through a corner of the box is not claimed, whatever the margin's
// rounding: the box touches the pixel's pyramid.
TEST(CameraPixels, ABoxTouchingThePixelsCornerRayIsNotClaimed) {
  SceneCamera camera;
  camera.eye = {1.0f, 2.0f, 3.0f};
  camera.target = {1.5f, 1.0f, -4.0f};
  const int width = 32, height = 32;
  const CameraParams cam = make_camera_params(camera, width, height);
  int checked = 0;
  for (int y = 0; y < height; y += 5)
    for (int x = 0; x < width; x += 5) {
      const co_vec3 d = camera_direction(&cam, width, height, x, y, 0.0f, 0.0f);
      const co_vec3 at = v3(cam.eye.x + 7.0f * d.x, cam.eye.y + 7.0f * d.y, cam.eye.z + 7.0f * d.z);
      // boxes with that point as one of their corners, reaching away in each of the eight octants
      for (int octant = 0; octant < 8; ++octant) {
        co_vec3 lo = at, hi = at;
        (octant & 1 ? lo.x : hi.x) += octant & 1 ? -0.5f : 0.5f;
        (octant & 2 ? lo.y : hi.y) += octant & 2 ? -0.5f : 0.5f;
        (octant & 4 ? lo.z : hi.z) += octant & 4 ? -0.5f : 0.5f;
        EXPECT_FALSE(camera_pixel_misses_box(&cam, width, height, x, y, lo, hi)) << x << "," << y << " octant " << octant;
        ++checked;
      }
    }
  EXPECT_EQ(checked, 7 * 7 * 8);
}

}  // namespace
