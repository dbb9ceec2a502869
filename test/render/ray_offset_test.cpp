// Ray offsets from floating-point error bounds (kernels/common/accel/ray_offset.h): the image does not
// depend on the scene's size or bounds, surfaces far from the origin show no acne, a gap thinner
// than any fraction of the scene leaks no light, and shadow rays reach lights exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "render_fixture.h"
#include "scene_building.h"

using namespace cohort;
using namespace cohort::test;

namespace {

PreparedScene cornell_box() { return prepare_scene(shipped_scene("cornell-box.gltf")); }

RenderSettings cornell_settings() {
  RenderSettings s;
  s.width = s.height = 48;
  s.spp = 16;
  s.max_depth = 6;
  return s;
}

// The scene and its camera scaled by `k` about the origin.
PreparedScene scaled(const PreparedScene& p, float k) {
  Scene s = p.scene;
  for (auto& v : s.positions) v *= k;
  SceneCamera c = p.camera;
  c.eye *= k;
  c.target *= k;
  return prepare(std::move(s), c);
}

std::size_t identical_pixels(const Image& a, const Image& b) {
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) same += std::memcmp(&a.rgb[i], &b.rgb[i], 3 * sizeof(float)) == 0;
  return same;
}

// The experiment: one tiny triangle far away changes nothing but the bounds (and the
// KD-tree). Paths never reach it behind the box, so every pixel must stay the same bit for bit;
// with an offset of 1e-4 x the diagonal every pixel moved.
TEST(RayOffset, AFarAwayTinyTriangleChangesNoPixel) {
  const PreparedScene box = cornell_box();
  Scene with = box.scene;
  SceneMaterial grey;  // not emissive: the light table stays the same
  grey.base_color = glm::vec3(0.5f);
  with.materials.push_back(grey);
  const auto material = std::uint32_t(with.materials.size() - 1);
  add_triangle(with, {0.f, 0.f, 50000.f}, {10.f, 0.f, 50000.f}, {0.f, 10.f, 50000.f}, material);
  const PreparedScene far = prepare(std::move(with), box.camera);
  ASSERT_GT(glm::length(far.scene.bounds().hi - box.scene.bounds().hi), 40000.f);
  const RenderSettings s = cornell_settings();
  const Image a = render_prepared(box, s).image, b = render_prepared(far, s).image;
  EXPECT_EQ(identical_pixels(a, b), std::size_t(s.width) * s.height);
}

// Scaling by a power of two is exact in floating point, and so is every offset: without NEE the
// same image bit for bit (any absolute constant in the offsets breaks this); with NEE, whose light
// sampling rounds a little differently at another scale, the image mean within 1e-4 (rounding, far
// below the noise of an independent render).
TEST(RayOffset, APowerOfTwoScaleGivesTheSameImage) {
  const PreparedScene box = cornell_box();
  for (const bool nee : {false, true}) {
    RenderSettings s = cornell_settings();
    s.nee = nee;
    const Image reference = render_prepared(box, s).image;
    for (const float k : {0x1p-10f, 0x1p10f}) {
      const Image image = render_prepared(scaled(box, k), s).image;
      if (!nee) {
        EXPECT_EQ(identical_pixels(image, reference), std::size_t(s.width) * s.height) << "scale " << k;
      }
      const double mean = channel_stats(image, 1).mean, reference_mean = channel_stats(reference, 1).mean;
      EXPECT_NEAR(mean, reference_mean, 1e-4 * reference_mean) << "scale " << k << ", NEE " << nee;
    }
  }
}

// Scaled by 1e-3 and 1e3 (not exact in binary) the image agrees within noise.
TEST(RayOffset, ScalingByAThousandKeepsTheImage) {
  const PreparedScene box = cornell_box();
  RenderSettings s = cornell_settings();
  s.width = s.height = 64;
  s.spp = 32;
  const Image reference = render_prepared(box, s).image;
  for (const float k : {1e-3f, 1e3f}) {
    RenderSettings other = s;
    other.seed = 7;  // independent noise, so the bound below is the noise of a difference
    expect_same_expectation(render_prepared(scaled(box, k), other).image, reference, "scale " + std::to_string(k));
  }
}

// A Lambertian plane of albedo 0.5 under a constant sky of 1, seen from above, two segments: every
// sample is exactly 0.5 unless its bounce hits the plane itself (acne, 0). The plane is tilted,
// cut into 32 triangles and placed at `centre`, `size` across.
void expect_no_acne(glm::vec3 centre, float size) {
  Scene s;
  SceneMaterial grey;
  grey.base_color = glm::vec3(0.5f);
  s.materials = {grey};
  const glm::vec3 n = glm::normalize(glm::vec3(1.f, 2.f, 3.f));
  const glm::vec3 u = glm::normalize(glm::cross(n, glm::vec3(0.f, 0.f, 1.f))) * (size / 4.f);
  const glm::vec3 v = glm::cross(n, u);
  // each vertex computed once, so neighbouring triangles share it exactly (no cracks)
  const auto vertex = [&](int i, int j) { return centre + float(i) * u + float(j) * v; };
  for (int i = -2; i < 2; ++i)
    for (int j = -2; j < 2; ++j) {
      add_triangle(s, vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), 0);
      add_triangle(s, vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1), 0);
    }
  const PreparedScene p = prepare(std::move(s), SceneCamera{centre + n * size, centre, v, 40.f});
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.spp = 16;
  settings.max_depth = 2;
  settings.russian_roulette = false;
  settings.environment = glm::vec3(1.f);
  const Image image = render_prepared(p, settings).image;
  for (const float value : image.rgb) ASSERT_NEAR(value, 0.5f, 1e-5f) << "centre " << centre.x << ", size " << size;
}

TEST(RayOffset, NoAcneFarFromTheOrigin) { expect_no_acne({3e5f, -1e5f, 2e5f}, 20.f); }
TEST(RayOffset, NoAcneOnATinySceneOffTheOrigin) { expect_no_acne({1e-7f, 2e-7f, -1e-7f}, 1e-8f); }
TEST(RayOffset, NoAcneOnAHugeScene) { expect_no_acne({0.f, 0.f, 0.f}, 1e7f); }

// A slab resting 0.01 above a 200-wide floor (a box on a plane): the camera sits in the slot and
// sees floor and slab, which only light entering 5 units away through the slot can reach. An
// offset of 1e-4 x the diagonal (0.028) starts every bounce above the slab, under the open sky.
TEST(RayOffset, AThinGapLeaksNoLight) {
  Scene s;
  SceneMaterial grey;
  grey.base_color = glm::vec3(0.5f);
  s.materials = {grey};
  add_quad(s, {-100.f, 0.f, -100.f}, {0.f, 0.f, 200.f}, {200.f, 0.f, 0.f}, 0);
  add_quad(s, {-5.f, 0.01f, -5.f}, {10.f, 0.f, 0.f}, {0.f, 0.f, 10.f}, 0);
  const PreparedScene p = prepare(std::move(s), SceneCamera{{0.f, 0.005f, 0.f}, {1.f, 0.f, 0.2f}, {0.f, 1.f, 0.f}, 60.f});
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.spp = 16;
  settings.max_depth = 6;
  settings.environment = glm::vec3(1.f);
  EXPECT_LT(channel_stats(render_prepared(p, settings).image, 0).mean, 0.01);
}

// A square light of half-width 1, facing down from height 1 over a Lambertian floor, on a ceiling
// that lies in its plane; the scene is 200 wide. Direct light only, NEE without MIS, seen at the
// point under the light's centre.
struct LightOverFloor {
  PreparedScene scene;
  RenderSettings settings;
};

LightOverFloor light_over_floor(bool occluder) {
  Scene s;
  SceneMaterial grey, light;
  grey.base_color = glm::vec3(0.5f);
  grey.double_sided = true;
  light.base_color = glm::vec3(0.f);
  light.emission = glm::vec3(2.f);
  s.materials = {grey, light};
  add_quad(s, {-100.f, 0.f, -100.f}, {0.f, 0.f, 200.f}, {200.f, 0.f, 0.f}, 0);  // floor, facing up
  add_quad(s, {-100.f, 1.f, -100.f}, {200.f, 0.f, 0.f}, {0.f, 0.f, 200.f}, 0);  // ceiling, facing down
  add_quad(s, {-1.f, 1.f, -1.f}, {2.f, 0.f, 0.f}, {0.f, 0.f, 2.f}, 1);          // the light, in the ceiling
  // 0.005 below the light (less than 1e-4 of the diagonal, more than its error bound)
  if (occluder) add_quad(s, {-1.5f, 0.995f, -1.5f}, {3.f, 0.f, 0.f}, {0.f, 0.f, 3.f}, 0);
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.spp = 256;
  settings.max_depth = 2;
  settings.mis = false;
  return {prepare(std::move(s), SceneCamera{{0.f, 0.5f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f}, 0.5f}), settings};
}

TEST(RayOffset, ShadowRaysReachALightInASurface) {
  const LightOverFloor l = light_over_floor(false);
  const PixelStats got = channel_stats(render_prepared(l.scene, l.settings).image, 0);
  // albedo x radiance x the form factor of a square of half-width X (in heights) to the point
  // under its centre
  const double x = 1.0 / std::sqrt(2.0);
  const double form_factor = 4.0 / M_PI * x * std::atan(x);
  EXPECT_NEAR(got.mean, 0.5 * 2.0 * form_factor, 5 * got.standard_error + 1e-3);
}

TEST(RayOffset, AnOccluderJustInFrontOfALightBlocksIt) {
  const LightOverFloor l = light_over_floor(true);
  EXPECT_EQ(channel_stats(render_prepared(l.scene, l.settings).image, 0).mean, 0.0);
}

}  // namespace
