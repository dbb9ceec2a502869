// glTF KHR_materials_volume (kernels/common/shading/medium.h, docs/bsdf.md "Volumes"): the interior of
// a transmissive material absorbs exp(-sigma_a d) over the distance d a path or a shadow ray travels
// inside, every method and tree gives the same bits with it, and a scene without an absorbing volume
// compiles and renders as before.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "kernels/common/shading/medium.h"
#include "method_tree_agreement.h"
#include "render_fixture.h"
#include "runtime/backend/device_support.h"
#include "runtime/render/methods/methods.h"
#include "scene_building.h"

using namespace cohort;
using namespace cohort::test;

namespace {

// A closed axis-aligned box, front faces outwards.
void add_box(Scene& s, glm::vec3 lo, glm::vec3 hi, std::uint32_t material) {
  const glm::vec3 d = hi - lo;
  add_quad(s, lo, {0, d.y, 0}, {d.x, 0, 0}, material);                        // z = lo.z, facing -z
  add_quad(s, {lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, d.y, 0}, material);        // z = hi.z, facing +z
  add_quad(s, lo, {0, 0, d.z}, {0, d.y, 0}, material);                        // x = lo.x, facing -x
  add_quad(s, {hi.x, lo.y, lo.z}, {0, d.y, 0}, {0, 0, d.z}, material);        // x = hi.x, facing +x
  add_quad(s, lo, {d.x, 0, 0}, {0, 0, d.z}, material);                        // y = lo.y, facing -y
  add_quad(s, {lo.x, hi.y, lo.z}, {0, 0, d.z}, {d.x, 0, 0}, material);        // y = hi.y, facing +y
}

// Smooth glass of IOR `ior` (1: an invisible interface, nothing reflected or bent) absorbing `sigma`.
SceneMaterial absorbing_glass(glm::vec3 sigma, float ior = 1.f, float roughness = 0.f) {
  SceneMaterial m;
  m.base_color = glm::vec3(1.f);
  m.metallic = 0.f;
  m.roughness = roughness;
  m.transmission = 1.f;
  m.ior = ior;
  m.absorption = sigma;
  return m;
}

// The camera looks down -z through a narrow field at the slab's front face (z = 0).
const SceneCamera kThroughSlab{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 1.f};

RenderSettings under_white_sky() {
  RenderSettings rs;
  rs.width = rs.height = 8;
  rs.spp = 4;
  rs.environment = glm::vec3(1.f);
  rs.rr_depth = 64;  // no roulette: every sample is the transmittance itself
  return rs;
}

}  // namespace

// The device's exp rounds as the host's: adds, multiplies, floor and bits only (medium.h). Within 2
// ulp of the correctly rounded value over the range transmittance uses, 0 below it, exact at 0.
TEST(GltfVolume, ExpIsAccurateAndExactAtTheEnds) {
  EXPECT_EQ(co_exp(0.f), 1.f);
  EXPECT_EQ(co_exp(-std::numeric_limits<float>::infinity()), 0.f);
  EXPECT_EQ(co_exp(-86.5f), 0.f);
  EXPECT_TRUE(std::isnan(co_exp(std::numeric_limits<float>::quiet_NaN())));
  int worst = 0;
  for (float x = -86.f; x <= 0.f; x += 0.001337f) {
    const float want = static_cast<float>(std::exp(double(x)));
    const float got = co_exp(x);
    std::int32_t a, b;
    std::memcpy(&a, &want, 4);
    std::memcpy(&b, &got, 4);
    worst = std::max(worst, std::abs(a - b));
  }
  EXPECT_LE(worst, 2) << "ulp";
  // a channel that does not absorb passes everything, even over an infinite distance
  EXPECT_EQ(medium_transmittance1(0.f, std::numeric_limits<float>::infinity()), 1.f);
  EXPECT_EQ(medium_transmittance1(0.5f, std::numeric_limits<float>::infinity()), 0.f);
  EXPECT_EQ(medium_transmittance1(std::numeric_limits<float>::max(), 0.f), 1.f);
}

// A slab of thickness d between two invisible interfaces (IOR 1): each channel of the sky seen
// through it is exp(-sigma d), up to the 1/cos of the half-degree the field spans and the ray offsets.
TEST(GltfVolume, ASlabAttenuatesByBeerLambert) {
  const float d = 0.5f;
  const glm::vec3 sigma{0.f, 1.f, 3.f};
  Scene s;
  s.materials = {absorbing_glass(sigma)};
  add_box(s, {-1, -1, -d}, {1, 1, 0}, 0);
  const PreparedScene p = prepare(s, kThroughSlab);
  ASSERT_TRUE(p.tables.features.volume);
  EXPECT_NE(p.tables.features.build_options().find("-DCOHORT_FEATURE_VOLUME"), std::string::npos);
  const Image image = render_prepared(p, under_white_sky()).image;
  for (int c = 0; c < 3; ++c) {
    const double want = std::exp(-double(sigma[c]) * d);
    for (int i = 0; i < image.width * image.height; ++i) {
      const double got = image.rgb[3 * std::size_t(i) + std::size_t(c)];
      // longer by up to 1/cos(0.7 degrees) - 1 = 7.5e-5 of d off the axis; shorter by the ray offsets
      // (ray_offset.h: about 1.3e-5 at vertices of magnitude 1), which the segment starts after
      EXPECT_LE(got, want * (1 + 1e-4)) << "channel " << c;
      EXPECT_GE(got, want * (1 - 3e-4)) << "channel " << c;
    }
  }
  EXPECT_EQ(mean_of(image, 0), 1.0) << "a channel that does not absorb passes the sky exactly";
}

// An open volume (one sheet, entered and never left): the path escapes from inside over an infinite
// distance, so the absorbing channels send nothing back, the other one all of the sky.
TEST(GltfVolume, EscapingFromInsideAnOpenVolumeIsAbsorbed) {
  Scene s;
  s.materials = {absorbing_glass({0.f, 0.2f, 1e-3f})};
  add_quad(s, {-4, -4, 0}, {8, 0, 0}, {0, 8, 0}, 0);
  const Image image = render_prepared(prepare(s, kThroughSlab), under_white_sky()).image;
  EXPECT_EQ(mean_of(image, 0), 1.0);
  EXPECT_EQ(mean_of(image, 1), 0.0);
  EXPECT_EQ(mean_of(image, 2), 0.0);
}

namespace {

// An absorbing box of invisible glass with a light and a floor inside, seen from outside: every
// light path ends inside the volume, and the shadow rays from the floor to the light run inside it.
Scene light_inside_a_volume(float roughness, float ior) {
  Scene s;
  SceneMaterial floor;
  floor.base_color = glm::vec3(0.8f);
  SceneMaterial light;
  light.base_color = glm::vec3(0.f);
  light.emission = glm::vec3(6.f);
  s.materials = {absorbing_glass({0.2f, 0.7f, 1.6f}, ior, roughness), floor, light};
  add_box(s, {-1, 0, -1}, {1, 2, 1}, 0);
  add_quad(s, {-0.9f, 0.05f, 0.9f}, {1.8f, 0, 0}, {0, 0, -1.8f}, 1);  // facing up
  add_quad(s, {-0.3f, 1.8f, -0.3f}, {0.6f, 0, 0}, {0, 0, 0.6f}, 2);   // facing down
  return s;
}

const SceneCamera kIntoTheBox{{0.f, 1.2f, 4.f}, {0.f, 0.8f, 0.f}, {0.f, 1.f, 0.f}, 35.f};

}  // namespace

// NEE's shadow rays inside the volume are absorbed as the paths that hit the light are: with and
// without NEE (BSDF sampling alone) the images agree in expectation. Unabsorbed shadow rays would
// make the NEE image brighter by up to 1 / exp(-1.6 x 1.75) = 16x in blue.
TEST(GltfVolume, ShadowRaysInsideAVolumeAreAbsorbedAsPathsAre) {
  const PreparedScene p = prepare(light_inside_a_volume(0.f, 1.f), kIntoTheBox);
  RenderSettings rs;
  rs.width = rs.height = 32;
  rs.spp = 256;
  rs.max_depth = 4;
  rs.seed = 3;
  const Image with_nee = render_prepared(p, rs).image;
  rs.nee = false;
  rs.seed = 5;
  const Image without = render_prepared(p, rs).image;
  for (int c = 0; c < 3; ++c) EXPECT_GT(mean_of(with_nee, c), 1e-3) << "a black image proves nothing";
  expect_same_expectation(with_nee, without, "NEE against BSDF sampling");
}

// A transmissive material without an absorbing interior, or an absorbing one that cannot transmit,
// selects no volume code (the program of such a scene is the one before volumes, token for token,
// but for the Material's added field); and the volume code itself, forced on for a scene whose
// glass absorbs nothing, changes no bit of its image.
TEST(GltfVolume, ASceneWithoutAnAbsorbingVolumeIsUnaffected) {
  const auto scene = [](glm::vec3 sigma, float transmission) {
    Scene s = light_inside_a_volume(0.3f, 1.5f);
    s.materials[0].absorption = sigma;
    s.materials[0].transmission = transmission;
    return prepare(s, kIntoTheBox);
  };
  const PreparedScene plain = scene(glm::vec3(0.f), 1.f);
  EXPECT_FALSE(plain.tables.features.volume);
  EXPECT_EQ(plain.tables.features.build_options(), "-DCOHORT_FEATURE_DIELECTRIC");
  const PreparedScene opaque = scene({1.f, 1.f, 1.f}, 0.f);
  EXPECT_FALSE(opaque.tables.features.volume);
  EXPECT_EQ(opaque.tables.features.build_options().find("VOLUME"), std::string::npos);
  EXPECT_TRUE(scene({1.f, 0.f, 0.f}, 0.5f).tables.features.volume);
  PreparedScene forced = scene(glm::vec3(0.f), 1.f);
  forced.tables.features.volume = true;
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.spp = 4;
  rs.seed = 4;
  rs.environment = glm::vec3(0.2f);
  const RenderResult a = render_prepared(plain, rs);
  const RenderResult b = render_prepared(forced, rs);
  EXPECT_GT(mean_of(a.image, 0), 1e-3) << "a black image proves nothing";
  EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * sizeof(float)));
  EXPECT_EQ(a.rays, b.rays);
}

// Every method on every tree gives the naive image bit for bit: the medium travels in the path
// slot's throughput lane through pools that refill, the sort's gathered payload and the resumed
// walks, and the segment length comes from the hit's barycentrics, which they all agree on.
TEST(GltfVolume, EveryMethodAndTreeGivesTheSameBits) {
  Scene room = light_inside_a_volume(0.f, 1.5f);
  // a rough sphere of another absorbing glass beside the box: NEE through its boundary, reflections inside
  room.materials.push_back(absorbing_glass({1.2f, 0.4f, 0.1f}, 1.33f, 0.3f));
  add_sphere(room, {1.8f, 0.6f, 0.5f}, 0.6f, 3, 2);
  add_quad(room, {-4, -0.01f, 4}, {8, 0, 0}, {0, 0, -8}, 1);
  RenderSettings s;
  s.width = 24;
  s.height = 20;
  s.spp = 3;
  s.rr_depth = 3;
  s.seed = 9;
  s.environment = glm::vec3(0.3f);
  s.sort.sort_from_bounce = 1;
  expect_every_method_and_tree_agree(
      "volume-room", room, kIntoTheBox, s,
      [](const PreparedScene& p, const char* tree) { ASSERT_TRUE(p.tables.features.volume) << tree; },
      [](const Image& image) { return mean_of(image, 2) > 0.005; });
}
