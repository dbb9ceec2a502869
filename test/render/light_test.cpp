// Lights beyond emissive triangles (docs/lights.md): the environment map against the constant
// environment and between its sampling strategies, point and spot lights against closed forms,
// every method bit for bit with them, and the feature options they compile.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "kernels/common/shading/camera.h"
#include "kernels/common/shading/punctual.h"
#include "render_fixture.h"
#include "runtime/render/scene/camera_params.h"
#include "runtime/render/scene/environment_map.h"
#include "scene_building.h"

using namespace cohort;
using namespace cohort::test;

namespace {

// A Lambertian sphere on a Lambertian ground, open to the sky.
PreparedScene sphere_on_ground() {
  Scene s;
  SceneMaterial ground, ball;
  ground.base_color = glm::vec3(0.5f);
  ball.base_color = glm::vec3(0.8f, 0.6f, 0.3f);
  s.materials = {ground, ball};
  add_quad(s, {-4.f, 0.f, 4.f}, {8.f, 0.f, 0.f}, {0.f, 0.f, -8.f}, 0);
  add_sphere(s, {0.f, 1.f, 0.f}, 1.f, 1, 2);
  return prepare(s, SceneCamera{{0.f, 2.5f, 5.f}, {0.f, 0.8f, 0.f}, {0.f, 1.f, 0.f}, 45.f});
}

// Sky gradient, a sun and a black band: a map the sampler must follow.
Image sky_image(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      const float t = 1.f - float(y) / float(h - 1);
      p[0] = 0.3f + 0.3f * t, p[1] = 0.4f + 0.4f * t, p[2] = 0.6f + 0.6f * t;
      if (y == h - 2) p[0] = p[1] = p[2] = 0.f;
    }
  float* sun = img.pixel(w / 3, h / 4);
  sun[0] = 60.f, sun[1] = 50.f, sun[2] = 40.f;
  return img;
}

RenderSettings small_settings(std::uint32_t spp) {
  RenderSettings rs;
  rs.width = rs.height = 64;
  rs.spp = spp;
  rs.seed = 3;
  rs.max_depth = 4;
  return rs;
}

}  // namespace

TEST(EnvironmentMap, ConstantMapRendersAsTheConstantEnvironment) {
  PreparedScene p = sphere_on_ground();
  RenderSettings rs = small_settings(64);
  rs.environment = glm::vec3(0.8f, 0.6f, 0.4f);
  const RenderResult constant = render_prepared(p, rs);
  Image flat(16, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) flat.pixel(x, y)[0] = 0.8f, flat.pixel(x, y)[1] = 0.6f, flat.pixel(x, y)[2] = 0.4f;
  set_environment_map(p.tables, make_environment_map(flat, "flat"));
  const RenderResult mapped = render_prepared(p, rs);
  EXPECT_EQ(mapped.dropped_samples, 0u);
  expect_same_expectation(mapped.image, constant.image, "constant map vs --env");
}

TEST(EnvironmentMap, NeeMisAndBsdfSamplingAgree) {
  PreparedScene p = sphere_on_ground();
  set_environment_map(p.tables, make_environment_map(sky_image(32, 16), "sky"));
  RenderSettings rs = small_settings(128);
  const RenderResult mis = render_prepared(p, rs);
  rs.mis = false;
  const RenderResult nee_only = render_prepared(p, rs);
  rs.nee = false;
  rs.spp = 512;  // BSDF sampling alone finds the sun rarely
  const RenderResult bsdf_only = render_prepared(p, rs);
  expect_same_expectation(mis.image, bsdf_only.image, "NEE+MIS vs BSDF sampling");
  expect_same_expectation(nee_only.image, bsdf_only.image, "NEE alone vs BSDF sampling");
}

// ---- Punctual lights against closed forms --------------------------------------------------------

namespace {

constexpr float kAlbedo = 0.6f;

// A Lambertian ground (y = 0) lit by one light, seen from above; direct light only.
PreparedScene lit_ground(const SceneLight& light) {
  Scene s;
  SceneMaterial ground;
  ground.base_color = glm::vec3(kAlbedo);
  s.materials = {ground};
  add_quad(s, {-6.f, 0.f, 6.f}, {12.f, 0.f, 0.f}, {0.f, 0.f, -12.f}, 0);
  s.lights = {light};
  return prepare(s, SceneCamera{{0.f, 6.f, 4.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 60.f});
}

// glTF's spot falloff, written from the specification in double precision.
double gltf_spot(const SceneLight& l, const glm::dvec3& to_receiver) {
  if (l.type != SceneLight::Type::spot) return 1.0;
  const double cos_outer = std::cos(double(l.outer_cone)), cos_inner = std::cos(double(l.inner_cone));
  const double scale = 1.0 / std::max(0.001, cos_inner - cos_outer), offset = -cos_outer * scale;
  const double cd = glm::dot(glm::dvec3(l.direction), to_receiver);
  const double a = std::clamp(cd * scale + offset, 0.0, 1.0);
  return a * a;
}

// Radiance of the ground point seen through (x + jx, y + jy): albedo / pi * I cos / r^2.
double analytic_radiance(const CameraParams& cam, const SceneLight& l, int w, int h, int x, int y, float jx,
                         float jy, int channel) {
  const co_vec3 d = camera_direction(&cam, w, h, x, y, jx, jy);
  const double t = -double(cam.eye.y) / d.y;
  if (!(t > 0)) return 0;
  const glm::dvec3 p(cam.eye.x + t * d.x, 0.0, cam.eye.z + t * d.z);
  if (std::abs(p.x) > 6 || std::abs(p.z) > 6) return 0;
  const glm::dvec3 to_light = glm::dvec3(l.position) - p;
  const double r2 = glm::dot(to_light, to_light), r = std::sqrt(r2);
  const double cos_theta = to_light.y / r;
  if (!(cos_theta > 0)) return 0;
  return kAlbedo / M_PI * l.intensity[channel] * gltf_spot(l, -to_light / r) * cos_theta / r2;
}

// Every pixel's rendered radiance against the closed form averaged over the pixel (the camera
// jitter is the only randomness of a direct-lit Lambertian under a delta light): within 5
// standard errors of that jitter average, plus 1e-4 relative for float rounding.
void expect_analytic(const SceneLight& light, const char* what) {
  const PreparedScene p = lit_ground(light);
  RenderSettings rs = small_settings(64);
  rs.max_depth = 2;
  const RenderResult r = render_prepared(p, rs);
  const CameraParams cam = make_camera_params(p.camera, rs.width, rs.height);
  const int n = 12;  // jitter grid per pixel for the closed-form average
  int failures = 0, lit = 0;
  for (int y = 0; y < int(rs.height); ++y)
    for (int x = 0; x < int(rs.width); ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0, sum2 = 0;
        for (int j = 0; j < n * n; ++j) {
          const double v = analytic_radiance(cam, light, rs.width, rs.height, x, y, (j % n + 0.5f) / n,
                                             (j / n + 0.5f) / n, c);
          sum += v;
          sum2 += v * v;
        }
        const double mean = sum / (n * n), sd = std::sqrt(std::max(0.0, sum2 / (n * n) - mean * mean));
        const double bound = 5 * sd / std::sqrt(double(rs.spp)) + 1e-4 * mean + 1e-6;
        const double got = r.image.pixel(x, y)[c];
        lit += mean > 0;
        if (std::abs(got - mean) > bound) {
          if (++failures <= 5)
            ADD_FAILURE() << what << " pixel (" << x << ", " << y << ") channel " << c << ": " << got << " vs "
                          << mean << " +- " << bound;
        }
      }
  // a pixel straddling a spot's or the ground's edge can miss the 12 x 12 grid's average by more
  EXPECT_LE(failures, 3) << what;
  EXPECT_GT(lit, 300) << what << ": too little of the image is lit to prove anything";
}

}  // namespace

TEST(PunctualLights, PointLightOverLambertianPlaneMatchesInverseSquareLaw) {
  SceneLight point;
  point.position = glm::vec3(0.5f, 2.f, -0.5f);
  point.intensity = glm::vec3(10.f, 6.f, 3.f);
  expect_analytic(point, "point");
}

TEST(PunctualLights, SpotConeFollowsGltfFalloff) {
  SceneLight spot;
  spot.type = SceneLight::Type::spot;
  spot.position = glm::vec3(0.f, 3.f, 0.f);
  spot.direction = glm::normalize(glm::vec3(0.2f, -1.f, 0.1f));
  spot.intensity = glm::vec3(20.f);
  spot.inner_cone = 0.3f;
  spot.outer_cone = 0.6f;
  expect_analytic(spot, "spot");
  // the cone really cuts: the centre is lit, a point far outside the outer cone is black
  const PreparedScene p = lit_ground(spot);
  RenderSettings rs = small_settings(4);
  rs.max_depth = 2;
  const RenderResult r = render_prepared(p, rs);
  EXPECT_GT(r.image.pixel(32, 32)[0], 0.f);
  EXPECT_EQ(r.image.pixel(2, 2)[0], 0.f);
}

TEST(PunctualLights, FalloffHelperMatchesGltfReference) {
  SceneLight spot;
  spot.type = SceneLight::Type::spot;
  spot.direction = glm::vec3(0, -1, 0);
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.5f;
  PunctualTable t = make_punctual_table({spot});
  ASSERT_EQ(t.lights.size(), 1u);
  for (double angle = 0; angle < 0.7; angle += 0.01) {
    const glm::dvec3 d(std::sin(angle), -std::cos(angle), 0);
    EXPECT_NEAR(punctual_falloff(&t.lights[0], v3(float(d.x), float(d.y), float(d.z))), gltf_spot(spot, d), 1e-5)
        << angle;
  }
}

// ---- All methods, bit for bit, with every kind of light ------------------------------------------

TEST(Lights, EveryMethodRendersEveryLightBitForBit) {
  PreparedScene p = sphere_on_ground();
  SceneMaterial lamp;
  lamp.emission = glm::vec3(4.f);
  p.scene.materials.push_back(lamp);
  add_quad(p.scene, {-0.5f, 3.f, -0.5f}, {0.f, 0.f, 1.f}, {1.f, 0.f, 0.f}, 2);  // faces down
  SceneLight spot;
  spot.type = SceneLight::Type::spot;
  spot.position = glm::vec3(2.f, 3.f, 1.f);
  spot.direction = glm::normalize(glm::vec3(-2.f, -3.f, -1.f));
  spot.intensity = glm::vec3(5.f);
  SceneLight point;
  point.position = glm::vec3(-2.f, 1.5f, 1.f);
  point.intensity = glm::vec3(2.f, 1.f, 1.f);
  p.scene.lights = {spot, point};
  p = prepare(p.scene, p.camera);
  set_environment_map(p.tables, make_environment_map(sky_image(16, 8), "sky"));
  EXPECT_EQ(p.tables.features.build_options(), "-DCOHORT_FEATURE_ENVMAP -DCOHORT_FEATURE_PUNCTUAL");
  RenderSettings rs = small_settings(4);
  rs.width = rs.height = 32;
  rs.max_depth = 0;  // Russian roulette too
  const RenderResult reference = render_prepared(p, rs);
  EXPECT_GT(channel_stats(reference.image, 0).mean, 0.05);
  for (const char* method : {"wavefront", "sc+rg", "pth"}) {
    rs.method = method;
    const RenderResult r = render_prepared(p, rs);
    EXPECT_EQ(r.image.rgb, reference.image.rgb) << method;
  }
}

TEST(Lights, FeatureOptionsOnlyWhenUsed) {
  PreparedScene p = sphere_on_ground();
  EXPECT_EQ(p.tables.features.build_options(), "");
  SceneLight point;
  p.scene.lights = {point};
  EXPECT_EQ(prepare(p.scene, p.camera).tables.features.build_options(), "-DCOHORT_FEATURE_PUNCTUAL");
  const PreparedScene cornell = prepare_scene(shipped_scene("cornell-box.gltf"));
  EXPECT_EQ(light_pick(cornell.tables, 1.f).triangles, 1.f);  // the estimator without other lights
}
