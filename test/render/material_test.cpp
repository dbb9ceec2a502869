// The BSDFs in the path tracer (docs/bsdf.md, "Integrating into the path tracer"): white furnaces
// for the energy-conserving BSDFs, scenes of glass, metal, plastic and textures that every method
// must render bit for bit like NAIVE, the feature options a scene's kernels are built with, and
// base-colour and emission textures.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "render_fixture.h"
#include "scene_building.h"
#include "runtime/render/methods/methods.h"
#include "kernels/common/shading/texture.h"

using namespace cohort;
using namespace cohort::test;

namespace {

struct Rendered {
  PreparedScene prepared;
  RenderResult result;
};

// ---- White furnace: an object in a uniform environment of radiance 1 ------------------------------

struct FurnaceObject {
  const char* name;
  SceneMaterial material;
  double tolerance;  // beyond 5 standard errors: BSDF albedos that are 1 only up to a fit
};

std::vector<FurnaceObject> furnace_objects() {
  std::vector<FurnaceObject> out;
  SceneMaterial glass;
  glass.base_color = glm::vec3(1.f);
  glass.transmission = 1.f;
  glass.roughness = 0.f;
  glass.ior = 1.5f;
  out.push_back({"smooth_glass", glass, 0});
  SceneMaterial water = glass;
  water.ior = 1.33f;
  out.push_back({"smooth_water", water, 0});
  SceneMaterial mirror;
  mirror.base_color = glm::vec3(1.f);
  mirror.metallic = 1.f;
  mirror.roughness = 0.f;
  out.push_back({"smooth_conductor_f0_1", mirror, 0});
  SceneMaterial white;
  white.base_color = glm::vec3(1.f);
  out.push_back({"lambertian_albedo_1", white, 0});
  // Mitsuba's F_dr fit makes the white smooth plastic's albedo 1 +- 1.5e-3 (docs/bsdf.md)
  SceneMaterial plastic = white;
  plastic.roughness = 0.f;
  out.push_back({"smooth_white_plastic", plastic, 2e-3});
  return out;
}

class WhiteFurnace : public ::testing::TestWithParam<std::tuple<std::size_t, const char*>> {};

TEST_P(WhiteFurnace, EnergyConservingObjectVanishes) {
  const FurnaceObject object = furnace_objects()[std::get<0>(GetParam())];
  Scene s;
  s.materials = {object.material};
  add_sphere(s, glm::vec3(0.f), 1.f, 0);
  const PreparedScene p = prepare(s, SceneCamera{{0.f, 0.f, 3.2f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f});
  RenderSettings rs;
  rs.width = rs.height = 32;
  rs.spp = 64;
  rs.seed = 5;
  rs.rr_depth = 3;  // Russian roulette inside the glass, where refraction scales the throughput
  rs.environment = glm::vec3(1.f);
  rs.method = std::get<1>(GetParam());
  const RenderResult r = render_prepared(p, rs);
  EXPECT_EQ(r.dropped_samples, 0u);
  for (int ch = 0; ch < 3; ++ch) {
    const PixelStats st = channel_stats(r.image, ch);
    EXPECT_NEAR(st.mean, 1.0, 5 * st.standard_error + 1e-4 + object.tolerance)
        << object.name << " channel " << ch << " stderr " << st.standard_error;
  }
}

INSTANTIATE_TEST_SUITE_P(Sphere, WhiteFurnace,
                         ::testing::Combine(::testing::Range<std::size_t>(0, furnace_objects().size()),
                                            ::testing::Values("naive", "sc+rg")),
                         [](const auto& info) {
                           std::string method = std::get<1>(info.param);
                           for (char& ch : method)
                             if (ch == '+') ch = '_';
                           return std::string(furnace_objects()[std::get<0>(info.param)].name) + "_" + method;
                         });

// Lossless objects inside the emitting furnace (Le = 1, albedo 0.5, so radiance 2 everywhere
// outside the objects): a mirror of F0 = 1, a glass sphere and a white Lambertian leave the uniform
// field unchanged. This checks NEE, MIS and the delta-lobe rules together: no NEE at a delta
// vertex, weight 1 for the emitter hit after a delta sample, shadow rays blocked by glass.
struct FurnaceMode {
  const char* name;
  bool nee, mis;
};

class ObjectsInFurnace : public ::testing::TestWithParam<std::tuple<FurnaceMode, const char*>> {};

TEST_P(ObjectsInFurnace, KeepTheUniformRadiance) {
  Scene s;
  SceneMaterial walls;
  walls.base_color = glm::vec3(0.5f);
  walls.emission = glm::vec3(1.f);
  SceneMaterial mirror;
  mirror.base_color = glm::vec3(1.f);
  mirror.metallic = 1.f;
  mirror.roughness = 0.f;
  SceneMaterial glass;
  glass.base_color = glm::vec3(1.f);
  glass.transmission = 1.f;
  glass.roughness = 0.f;
  SceneMaterial white;
  white.base_color = glm::vec3(1.f);
  s.materials = {walls, mirror, glass, white};
  add_sphere(s, glm::vec3(0.f), 1.f, 0, 3, /*inward=*/true);
  add_sphere(s, {-0.4f, 0.f, 0.f}, 0.25f, 1, 2);
  add_sphere(s, {0.4f, 0.f, 0.f}, 0.25f, 2, 2);
  add_sphere(s, {0.f, -0.45f, 0.2f}, 0.2f, 3, 2);
  const PreparedScene p = prepare(s, SceneCamera{{0.f, 0.3f, 0.8f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 60.f});
  ASSERT_EQ(p.tables.features, (SceneFeatures{.conductor = true, .dielectric = true}));
  const FurnaceMode mode = std::get<0>(GetParam());
  RenderSettings rs;
  rs.width = rs.height = 32;
  rs.spp = 256;
  rs.seed = 3;
  rs.rr_depth = 3;
  rs.nee = mode.nee;
  rs.mis = mode.mis;
  rs.method = std::get<1>(GetParam());
  const RenderResult r = render_prepared(p, rs);
  EXPECT_EQ(r.dropped_samples, 0u);
  for (int ch = 0; ch < 3; ++ch) {
    const PixelStats st = channel_stats(r.image, ch);
    EXPECT_NEAR(st.mean, 2.0, 5 * st.standard_error + 2e-4) << mode.name << " channel " << ch << " stderr "
                                                            << st.standard_error;
  }
}

INSTANTIATE_TEST_SUITE_P(Sphere, ObjectsInFurnace,
                         ::testing::Combine(::testing::Values(FurnaceMode{"bsdf_only", false, false},
                                                              FurnaceMode{"nee_mis", true, true},
                                                              FurnaceMode{"nee_without_mis", true, false}),
                                            ::testing::Values("naive")),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param).name) + "_" + std::get<1>(info.param);
                         });

// ---- A closed room of glass, metal, plastic and textures: every method agrees with NAIVE -----------

Scene material_room() {
  Scene s;
  SceneMaterial white;
  white.base_color = glm::vec3(0.7f);
  SceneMaterial light;
  light.base_color = glm::vec3(0.5f);
  light.emission = glm::vec3(6.f);
  light.double_sided = true;
  SceneMaterial glass;
  glass.base_color = glm::vec3(1.f, 0.9f, 0.8f);
  glass.transmission = 1.f;
  glass.roughness = 0.f;
  SceneMaterial rough_glass = glass;
  rough_glass.roughness = 0.4f;
  SceneMaterial metal;
  metal.base_color = glm::vec3(0.95f, 0.7f, 0.3f);
  metal.metallic = 1.f;
  metal.roughness = 0.3f;
  SceneMaterial plastic;
  plastic.base_color = glm::vec3(0.2f, 0.4f, 0.8f);
  plastic.roughness = 0.f;
  SceneMaterial mixed;  // the stochastic glTF mix: metal, glass and rough plastic at one point
  mixed.base_color = glm::vec3(0.8f);
  mixed.metallic = 0.4f;
  mixed.transmission = 0.5f;
  mixed.roughness = 0.5f;
  SceneMaterial textured = white;
  textured.base_color = glm::vec3(1.f);
  textured.base_color_texture = add_texture(s, 8, 8, [](int x, int y) {
    return (x + y) % 2 ? std::array<std::uint8_t, 4>{230, 40, 40, 255} : std::array<std::uint8_t, 4>{40, 200, 90, 255};
  });
  SceneMaterial screen;  // emission texture on a front-only emitter
  screen.base_color = glm::vec3(0.1f);
  screen.emission = glm::vec3(3.f);
  screen.emission_texture = add_texture(s, 4, 2, [](int x, int y) {
    return std::array<std::uint8_t, 4>{std::uint8_t(60 * x), std::uint8_t(120 * y + 40), 200, 255};
  });
  s.materials = {white, light, glass, rough_glass, metal, plastic, mixed, textured, screen};

  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0.f);
  add_quad(s, o, z, x, 7, true);  // floor, textured
  add_quad(s, o + y, x, z, 0);    // ceiling
  add_quad(s, o, y, z, 0);
  add_quad(s, o + x, z, y, 0);
  add_quad(s, o, x, y, 0);
  add_quad(s, o + z, y, x, 0);
  add_quad(s, glm::vec3(0.4f, 0.99f, 0.4f), 0.2f * x, 0.2f * z, 1);
  add_quad(s, glm::vec3(0.02f, 0.3f, 0.4f), 0.2f * y, 0.3f * z, 8, true);  // screen by the x = 0 wall, facing +x
  add_sphere(s, {0.3f, 0.2f, 0.35f}, 0.15f, 2, 2);
  add_sphere(s, {0.7f, 0.2f, 0.35f}, 0.15f, 4, 2);
  add_sphere(s, {0.5f, 0.45f, 0.6f}, 0.12f, 3, 2);
  add_sphere(s, {0.25f, 0.6f, 0.65f}, 0.1f, 5, 2);
  add_sphere(s, {0.75f, 0.6f, 0.65f}, 0.1f, 6, 2);
  return s;
}

TEST(MaterialRoom, EveryMethodGivesTheReferenceImage) {
  const PreparedScene p = prepare(material_room(), SceneCamera{{0.5f, 0.5f, 0.02f}, {0.5f, 0.4f, 1.f}, {0, 1, 0}, 70});
  const SceneFeatures all{.textures = true, .conductor = true, .dielectric = true, .plastic = true};
  EXPECT_EQ(p.tables.features, all);
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, p.tree, p.tables);
  RenderSettings s;
  s.width = 24;
  s.height = 20;
  s.spp = 3;
  s.rr_depth = 3;
  s.seed = 9;
  const RenderResult reference = render(cl, cache, scene, p.camera, s);
  EXPECT_EQ(reference.dropped_samples, 0u);
  double sum = 0;
  for (float v : reference.image.rgb) sum += v;
  EXPECT_GT(sum, 0.0) << "a black image proves nothing";
  for (const auto& m : methods()) {
    if (!m.wavefront) continue;
    s.method = m.name;
    const RenderResult r = render(cl, cache, scene, p.camera, s);
    EXPECT_EQ(0, std::memcmp(reference.image.rgb.data(), r.image.rgb.data(), r.image.rgb.size() * sizeof(float)))
        << m.name << " differs from naive";
    EXPECT_EQ(reference.rays, r.rays) << m.name;
  }
}

// Camera inside a closed glass sphere inside the room: paths start in the dielectric's interior.
TEST(MaterialRoom, CameraInsideGlassAgreesAcrossMethods) {
  Scene room = material_room();
  add_sphere(room, {0.5f, 0.5f, 0.3f}, 0.1f, 2, 2);
  const PreparedScene p = prepare(room, SceneCamera{{0.5f, 0.5f, 0.3f}, {0.5f, 0.4f, 1.f}, {0, 1, 0}, 80});
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, p.tree, p.tables);
  RenderSettings s;
  s.width = 16;
  s.height = 12;
  s.spp = 2;
  s.rr_depth = 2;
  const RenderResult reference = render(cl, cache, scene, p.camera, s);
  double sum = 0;
  for (float v : reference.image.rgb) sum += v;
  EXPECT_GT(sum, 0.0);
  for (const char* method : {"wavefront", "sc+rg", "pth"}) {
    s.method = method;
    const RenderResult r = render(cl, cache, scene, p.camera, s);
    EXPECT_EQ(0, std::memcmp(reference.image.rgb.data(), r.image.rgb.data(), r.image.rgb.size() * sizeof(float)))
        << method << " differs from naive";
  }
}

// ---- Feature options -----------------------------------------------------------------------------

TEST(SceneFeatures, DiffuseOnlySceneDefinesNoFeature) {
  const PreparedScene cornell = prepare_scene(shipped_scene("cornell-box.gltf"));
  EXPECT_EQ(cornell.tables.features, SceneFeatures{});
  EXPECT_EQ(cornell.tables.features.build_options(), "");
  const ClContext cl(select_device(""));
  const DeviceScene scene = upload_scene(cl, cornell.tree, cornell.tables);
  EXPECT_EQ(scene.build_options.find("COHORT_FEATURE"), std::string::npos);
}

TEST(SceneFeatures, GlassSceneDefinesDielectricOnly) {
  Scene s;
  SceneMaterial glass;
  glass.transmission = 1.f;
  glass.roughness = 0.f;
  s.materials = {glass};
  add_sphere(s, glm::vec3(0.f), 1.f, 0, 1);
  const PreparedScene p = prepare(s, SceneCamera{});
  EXPECT_EQ(p.tables.features.build_options(), "-DCOHORT_FEATURE_DIELECTRIC");
  const ClContext cl(select_device(""));
  const DeviceScene scene = upload_scene(cl, p.tree, p.tables);
  EXPECT_NE(scene.build_options.find("-DCOHORT_FEATURE_DIELECTRIC"), std::string::npos);
  EXPECT_EQ(scene.build_options.find("CONDUCTOR"), std::string::npos);
}

TEST(SceneFeatures, FollowTheGltfMapping) {
  auto features = [](float metallic, float roughness, float transmission) {
    SceneMaterial m;
    m.metallic = metallic;
    m.roughness = roughness;
    m.transmission = transmission;
    return material_features(to_device_material(m));
  };
  EXPECT_EQ(features(0, 1, 0), SceneFeatures{});                                      // Lambertian
  EXPECT_EQ(features(0, 0.5f, 0), (SceneFeatures{.plastic = true}));
  EXPECT_EQ(features(1, 0.5f, 0), (SceneFeatures{.conductor = true}));                // metal only
  EXPECT_EQ(features(0, 0.2f, 1), (SceneFeatures{.dielectric = true}));               // glass only
  EXPECT_EQ(features(0.5f, 1, 0), (SceneFeatures{.conductor = true}));                // metal or diffuse
  EXPECT_EQ(features(0.5f, 0.5f, 0.5f), (SceneFeatures{.conductor = true, .dielectric = true, .plastic = true}));
  // with 0 < metallic < 1 the remapped number may round to 1, where transmission 1 does not catch it
  EXPECT_EQ(features(0.3f, 0.5f, 1), (SceneFeatures{.conductor = true, .dielectric = true, .plastic = true}));
  EXPECT_EQ(features(-1, 2, -1), SceneFeatures{});  // clamped like the kernel
}

TEST(SceneFeatures, UnusedMaterialsAndMissingCoordinatesCompileNothing) {
  Scene s;
  SceneMaterial white, glass;
  glass.transmission = 1.f;
  white.base_color_texture = add_texture(s, 2, 2, [](int, int) { return std::array<std::uint8_t, 4>{9, 9, 9, 255}; });
  s.materials = {white, glass};  // glass is never used; no texture coordinates
  add_sphere(s, glm::vec3(0.f), 1.f, 0, 1);
  const PreparedScene p = prepare(s, SceneCamera{});
  EXPECT_EQ(p.tables.features, SceneFeatures{});
  EXPECT_EQ(p.tables.materials[0].base_color_texture, -1);
  EXPECT_TRUE(p.tables.texels.empty());
}

// ---- Textures ------------------------------------------------------------------------------------

TEST(Texture, BilinearRepeatInLinearSpace) {
  // 2 x 1 texels: sRGB 0 and 255 in red; green constant 188 (0.5 linear within 0.3%)
  const std::array<std::uint32_t, 2> texels = {0xff00bc00u, 0xff00bcffu};
  const TextureDesc desc{0, 2, 1, 0};
  auto red = [&](float u, float v) { return texture_sample(&desc, texels.data(), 0, u, v).x; };
  EXPECT_EQ(red(0.25f, 0.5f), 0.f);  // texel centres
  EXPECT_EQ(red(0.75f, 0.5f), 1.f);
  EXPECT_FLOAT_EQ(red(0.5f, 0.5f), 0.5f);   // halfway, filtered after the decode
  EXPECT_FLOAT_EQ(red(0.f, 0.5f), 0.5f);    // the left edge wraps to the last texel
  EXPECT_FLOAT_EQ(red(1.25f, 0.5f), 0.f);   // repeat
  EXPECT_FLOAT_EQ(red(-0.25f, 7.f), 1.f);
  EXPECT_EQ(red(NAN, INFINITY), red(0.f, 0.f));
  EXPECT_NEAR(texture_sample(&desc, texels.data(), 0, 0.3f, 0.9f).y, 0.5029f, 1e-4f);
  EXPECT_EQ(co_srgb_to_linear[255], 1.f);
  EXPECT_NEAR(co_srgb_to_linear[128], 0.2158605f, 1e-7f);
}

// A convex Lambertian sphere under a white sky: every ray that hits it scatters once and escapes,
// so the image is exactly the albedo where the sphere is and 1 elsewhere.
TEST(Texture, BaseColourTextureIsTheAlbedo) {
  Scene s;
  SceneMaterial m;
  m.base_color = glm::vec3(1.f, 0.5f, 1.f);
  m.base_color_texture = add_texture(s, 3, 3, [](int, int) { return std::array<std::uint8_t, 4>{128, 255, 0, 255}; });
  s.materials = {m};
  add_sphere(s, glm::vec3(0.f), 1.f, 0, 2);
  s.uvs.assign(s.positions.size(), glm::vec2(0.37f, 0.81f));
  const PreparedScene p = prepare(s, SceneCamera{{0.f, 0.f, 2.5f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f});
  ASSERT_TRUE(p.tables.features.textures);
  RenderSettings rs;
  rs.width = rs.height = 8;  // the centre pixels see the sphere
  rs.spp = 4;
  rs.environment = glm::vec3(1.f);
  rs.max_depth = 2;
  const RenderResult r = render_prepared(p, rs);
  const float* centre = &r.image.rgb[3 * (4 * 8 + 4)];
  EXPECT_FLOAT_EQ(centre[0], co_srgb_to_linear[128]);
  EXPECT_FLOAT_EQ(centre[1], 0.5f);
  EXPECT_EQ(centre[2], 0.f);
}

// An emission texture multiplies the emission factor: a front-facing textured emitter seen
// directly (max depth 1) shows factor x decoded texel.
TEST(Texture, EmissionTextureMultipliesEmission) {
  Scene s;
  SceneMaterial m;
  m.emission = glm::vec3(2.f, 4.f, 8.f);
  m.emission_texture = add_texture(s, 1, 1, [](int, int) { return std::array<std::uint8_t, 4>{255, 128, 0, 255}; });
  s.materials = {m};
  add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0, true);
  const PreparedScene p = prepare(s, SceneCamera{{0.f, 0.f, 2.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 20.f});
  RenderSettings rs;
  rs.width = rs.height = 4;
  rs.spp = 2;
  rs.max_depth = 1;
  const RenderResult r = render_prepared(p, rs);
  for (std::size_t i = 0; i < r.image.rgb.size(); i += 3) {
    EXPECT_FLOAT_EQ(r.image.rgb[i], 2.f);
    EXPECT_FLOAT_EQ(r.image.rgb[i + 1], 4.f * co_srgb_to_linear[128]);
    EXPECT_EQ(r.image.rgb[i + 2], 0.f);
  }
}

// The damaged helmet renders with its albedo, metallic-roughness and emission textures, the same with
// every method.
TEST(Texture, DamagedHelmetRendersWithItsTextures) {
  const std::filesystem::path model =
      std::filesystem::path(COHORT_SHARED_SCENES) / "damaged-helmet-gltf/DamagedHelmet.gltf";
  if (!std::filesystem::exists(model)) GTEST_SKIP() << model << " is missing";
  PreparedScene p = prepare_scene(model);
  ASSERT_TRUE(p.tables.features.textures);
  EXPECT_FALSE(p.tables.texels.empty());
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, p.tree, p.tables);
  RenderSettings rs;
  rs.width = rs.height = 24;
  rs.spp = 2;
  rs.max_depth = 4;
  rs.environment = glm::vec3(1.f);
  const RenderResult textured = render(cl, cache, scene, p.camera, rs);
  EXPECT_EQ(textured.dropped_samples, 0u);
  rs.method = "pth";
  const RenderResult pth = render(cl, cache, scene, p.camera, rs);
  EXPECT_EQ(0, std::memcmp(textured.image.rgb.data(), pth.image.rgb.data(), pth.image.rgb.size() * sizeof(float)));

  // without its textures the same model renders differently
  for (auto& m : p.scene.materials)
    m.base_color_texture = m.emission_texture = m.metallic_roughness_texture = m.normal_texture = -1;
  p.tables = make_scene_tables(p.scene, p.tree);
  EXPECT_FALSE(p.tables.features.textures);
  const DeviceScene plain_scene = upload_scene(cl, p.tree, p.tables);
  rs.method = "naive";
  const RenderResult plain = render(cl, cache, plain_scene, p.camera, rs);
  double difference = 0;
  for (std::size_t i = 0; i < plain.image.rgb.size(); ++i)
    difference += std::fabs(double(plain.image.rgb[i]) - textured.image.rgb[i]);
  EXPECT_GT(difference / plain.image.rgb.size(), 1e-3);
}

}  // namespace

