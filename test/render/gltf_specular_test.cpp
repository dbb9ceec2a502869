// glTF KHR_materials_specular in the path tracer (docs/bsdf.md, "Specular"): the kernel feature it
// selects, specular 0 as exactly the Lambertian, the white furnace, its textures against the factors
// they scale, and the same bits from every method and tree. The Mitsuba comparison is the reference
// scene `specular` (reference_scenes_test.cpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "method_tree_agreement.h"
#include "render_fixture.h"
#include "scene_building.h"
#include "kernels/common/shading/texture.h"

using namespace cohort;
using namespace cohort::test;

namespace {

SceneMaterial dielectric(glm::vec3 albedo, float roughness) {
  SceneMaterial m;
  m.base_color = albedo;
  m.metallic = 0.f;
  m.roughness = roughness;
  return m;
}

bool same_image(const RenderResult& a, const RenderResult& b) {
  return a.image.rgb.size() == b.image.rgb.size() &&
         std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * sizeof(float)) == 0;
}

// A texture of one texel whose A is 255: it forces the layering on a material of default factors.
int opaque_white(Scene& s) {
  return add_texture(s, 1, 1, [](int, int) { return std::array<std::uint8_t, 4>{255, 255, 255, 255}; },
                     TextureSampler{}, false);
}

TEST(GltfSpecular, OnlyAUsedNonDefaultSpecularSelectsTheFeature) {
  const SceneCamera camera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f};
  SceneMaterial plain = dielectric(glm::vec3(0.7f), 0.5f);
  SceneMaterial unused = plain;
  unused.specular.factor = 0.3f;
  SceneMaterial defaults = plain;  // the extension with its default values: the material without it
  defaults.specular.factor = 1.f;
  defaults.specular.color = glm::vec3(1.f);
  Scene s;
  s.materials = {plain, unused, defaults};
  add_quad(s, {-1, -1, 0}, {1, 0, 0}, {0, 2, 0}, 0, true);
  add_quad(s, {0, -1, 0}, {1, 0, 0}, {0, 2, 0}, 2, true);
  const PreparedScene none = prepare(s, camera);
  EXPECT_EQ(none.tables.features, SceneFeatures{.plastic = true}) << "no specular: no table, no option";
  EXPECT_TRUE(none.tables.material_specular.empty());
  EXPECT_TRUE(none.tables.textures.empty());

  s.materials[2].specular.color = glm::vec3(1.f, 0.5f, 1.f);
  const PreparedScene tinted = prepare(s, camera);
  EXPECT_EQ(tinted.tables.features, (SceneFeatures{.plastic = true, .specular = true}));
  ASSERT_EQ(tinted.tables.material_specular.size(), 3u);  // one entry per material
  EXPECT_EQ(tinted.tables.material_specular[2].color_factor.y, 0.5f);
  EXPECT_EQ(tinted.tables.material_specular[2].flags, MAT_SPECULAR_LAYER);
  EXPECT_EQ(tinted.tables.material_specular[0].flags, 0u) << "the plain material keeps its plastic";

  // default factors with a texture: the layering, and the texture goes up
  s.materials[2].specular.color = glm::vec3(1.f);
  s.materials[2].specular.texture = opaque_white(s);
  const PreparedScene textured = prepare(s, camera);
  EXPECT_EQ(textured.tables.features, (SceneFeatures{.textures = true, .plastic = true, .specular = true}));
  EXPECT_EQ(textured.tables.material_specular[2].factor_texture, 0);
}

// Specular 0 renders exactly the Lambertian of the base colour (a roughness-1 material without the
// extension), bit for bit, whatever its roughness and colour: no internal reflections added.
TEST(GltfSpecular, SpecularZeroIsExactlyTheLambertian) {
  const SceneCamera camera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f};
  Scene lambert;
  lambert.materials = {dielectric(glm::vec3(0.8f, 0.4f, 0.2f), 1.f)};
  add_sphere(lambert, {0.f, 0.f, 0.f}, 0.6f, 0, 3);
  RenderSettings rs = unbounded_white_sky(16, 8);
  rs.max_depth = 5;
  const RenderResult want = render_prepared(prepare(lambert, camera), rs);
  for (float roughness : {0.f, 0.4f, 1.f}) {
    Scene s = lambert;
    s.materials[0].roughness = roughness;
    s.materials[0].specular.factor = 0.f;
    s.materials[0].specular.color = glm::vec3(2.f, 1.f, 0.5f);
    const PreparedScene p = prepare(s, camera);
    ASSERT_TRUE(p.tables.features.specular);
    EXPECT_TRUE(same_image(render_prepared(p, rs), want)) << "roughness " << roughness;
  }
}

// A white Lambertian sphere with specular 1 and colour 1 (the layering forced by a white specular
// texture) under a white sky: smooth, every sample weighs 1 (the lobe F / q with q = F, the base 1); rough,
// at most 1 + 1e-3 on average (the lobe's albedo passes F(cos_i) a little, BSDF test
// SpecularLayer.WhiteFurnaceReflectsAtMostAll) and it loses its single-scattering shadowing.
TEST(GltfSpecular, AWhiteFurnaceStaysAtOne) {
  const SceneCamera camera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f};
  for (float roughness : {0.f, 0.3f, 1.f}) {
    Scene s;
    SceneMaterial m = dielectric(glm::vec3(1.f), roughness);
    m.specular.texture = opaque_white(s);
    s.materials = {m};
    add_sphere(s, {0.f, 0.f, 0.f}, 0.6f, 0, 3);
    const PreparedScene p = prepare(s, camera);
    ASSERT_TRUE(p.tables.features.specular);
    const RenderResult r = render_prepared(p, unbounded_white_sky(16, 64));
    double sum = 0, sum2 = 0, lo = 1e9, hi = 0;
    for (float v : r.image.rgb) {
      sum += v;
      sum2 += double(v) * v;
      lo = std::fmin(lo, v);
      hi = std::fmax(hi, v);
    }
    const double n = double(r.image.rgb.size()), mean = sum / n;
    const double sigma = std::sqrt(std::fmax(0.0, sum2 / n - mean * mean) / n);
    if (roughness == 0.f) {
      EXPECT_NEAR(lo, 1.0, 1e-5);
      EXPECT_NEAR(hi, 1.0, 1e-5);
    } else {
      EXPECT_LE(mean, 1.0 + 5.0 * sigma + 1e-3) << "roughness " << roughness;
      EXPECT_GT(mean, 0.9) << "roughness " << roughness;
    }
  }
}

// Two quads side by side and a floor. `textured`: one material whose specular texture (A) and colour
// texture (RGB, sRGB; nearest, each quad's coordinates at one texel's centre) say specular 77/255 and
// colour (1, 128, 0) on the left, specular 1 and colour (0, 64, 255) on the right; otherwise two
// materials with those factors. The same image bit for bit.
Scene specular_where_texture_says(bool textured) {
  Scene s;
  SceneMaterial base = dielectric(glm::vec3(0.3f, 0.5f, 0.2f), 0.3f);
  const auto texel = [](int x, int) {
    return x == 0 ? std::array<std::uint8_t, 4>{255, 128, 0, 77} : std::array<std::uint8_t, 4>{0, 64, 255, 255};
  };
  if (textured) {
    base.specular.color = glm::vec3(3.f);  // the factors multiply the textures
    base.specular.texture = add_texture(s, 2, 1, texel, TextureSampler{.nearest = true}, false);
    base.specular.color_texture = add_texture(s, 2, 1, texel, TextureSampler{.nearest = true}, true);
    s.materials = {base};
  } else {
    SceneMaterial left = base, right = base;
    left.specular.factor = 77 * (1.0f / 255.0f);  // as the kernel scales the factor 1 by the texel
    left.specular.color = 3.f * glm::vec3(co_srgb_to_linear[255], co_srgb_to_linear[128], co_srgb_to_linear[0]);
    right.specular.factor = 1.f;
    right.specular.color = 3.f * glm::vec3(co_srgb_to_linear[0], co_srgb_to_linear[64], co_srgb_to_linear[255]);
    s.materials = {left, right};
  }
  add_quad(s, {-1, -1, 0}, {1, 0, 0}, {0, 2, 0}, 0, true);
  add_quad(s, {0, -1, 0}, {1, 0, 0}, {0, 2, 0}, textured ? 0 : 1, true);
  for (std::size_t i = 0; i < s.uvs.size(); ++i) s.uvs[i] = glm::vec2(i < 6 ? 0.25f : 0.75f, 0.5f);
  add_quad(s, {-3, -1, -0.5f}, {6, 0, 0}, {0, 0, 3}, textured ? 0 : 1, true);  // a floor to reflect
  for (std::size_t i = 12; i < s.uvs.size(); ++i) s.uvs[i] = glm::vec2(0.75f, 0.5f);
  return s;
}

TEST(GltfSpecular, TexturesAreAlphaAndColour) {
  const SceneCamera camera{{0.f, 0.5f, 2.5f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f};
  const PreparedScene textured = prepare(specular_where_texture_says(true), camera);
  const PreparedScene factors = prepare(specular_where_texture_says(false), camera);
  ASSERT_TRUE(textured.tables.features.textures);
  ASSERT_TRUE(textured.tables.features.specular);
  RenderSettings rs = unbounded_white_sky(16, 3);
  rs.max_depth = 4;
  const RenderResult a = render_prepared(textured, rs), b = render_prepared(factors, rs);
  EXPECT_TRUE(same_image(a, b)) << "the textures' alpha and colour must give the factors' image bit for bit";
  EXPECT_EQ(a.rays, b.rays);
  // and the specular is there: without it the image differs
  Scene bare = specular_where_texture_says(false);
  for (SceneMaterial& m : bare.materials) m.specular = SceneSpecular{};
  EXPECT_FALSE(same_image(a, render_prepared(prepare(bare, camera), rs)));
}

// ---- Every method and tree gives the same bits with KHR_materials_specular -------------------------

// A closed room: a smooth tinted specular sphere, a wall of specular 0.4 at roughness 1, a partly
// metallic wall and a partly transmissive sphere with a specular (the layering takes their opaque
// dielectric share only), and a floor whose specular and colour come from textures (set 1 nearest,
// a transform bilinear); an area light in the ceiling.
Scene specular_room() {
  Scene s;
  SceneMaterial white = dielectric(glm::vec3(0.7f), 1.f);
  SceneMaterial light;
  light.emission = glm::vec3(6.f);
  light.double_sided = true;
  SceneMaterial sphere = dielectric(glm::vec3(0.8f, 0.2f, 0.1f), 0.f);
  sphere.specular.factor = 0.7f;
  sphere.specular.color = glm::vec3(0.5f, 2.f, 4.f);
  SceneMaterial wall = dielectric(glm::vec3(0.4f, 0.6f, 0.8f), 1.f);
  wall.specular.factor = 0.4f;
  SceneMaterial metal = dielectric(glm::vec3(0.9f), 0.4f);
  metal.metallic = 0.6f;
  metal.specular.factor = 0.2f;
  metal.specular.color = glm::vec3(1.f, 0.f, 0.f);
  SceneMaterial glass = dielectric(glm::vec3(1.f), 0.2f);
  glass.transmission = 0.7f;
  glass.ior = 1.4f;
  glass.specular.factor = 0.5f;
  SceneMaterial floor = dielectric(glm::vec3(0.3f, 0.6f, 0.4f), 0.5f);
  floor.specular.texture = add_texture(
      s, 4, 4, [](int x, int y) { return std::array<std::uint8_t, 4>{0, 0, 0, std::uint8_t((x + y) % 2 ? 255 : 40)}; },
      TextureSampler{.nearest = true, .wrap_s = TextureWrap::mirrored_repeat}, false);
  floor.specular.texcoord = 1;
  floor.specular.color_texture = add_texture(
      s, 3, 3, [](int x, int y) { return std::array<std::uint8_t, 4>{std::uint8_t(80 * x), 200, std::uint8_t(60 * y), 255}; },
      TextureSampler{}, true);
  floor.specular.color_transform = UvTransform{.offset = {0.2f, 0.1f}, .rotation = 0.3f, .scale = {1.5f, 0.8f}};
  floor.specular.color = glm::vec3(2.f);
  s.materials = {white, light, sphere, wall, metal, glass, floor};
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0.f);
  add_quad(s, o, z, x, 6, true);  // floor
  for (std::size_t i = 0; i < 6; ++i) s.uvs[i] = 2.5f * s.uvs[i] - 0.7f;
  s.uvs1.assign(s.positions.size(), glm::vec2(0.f));
  for (std::size_t i = 0; i < 6; ++i) s.uvs1[i] = glm::vec2(s.uvs[i].y, 1.3f * s.uvs[i].x);
  add_quad(s, o + y, x, z, 0);  // ceiling and walls, one of them the rough specular, one the metal
  add_quad(s, o, y, z, 3);
  add_quad(s, o + x, z, y, 4);
  add_quad(s, o, x, y, 0);
  add_quad(s, o + z, y, x, 0);
  add_quad(s, glm::vec3(0.4f, 0.99f, 0.4f), 0.2f * x, 0.2f * z, 1);
  add_sphere(s, {0.5f, 0.3f, 0.6f}, 0.2f, 2, 2);
  add_sphere(s, {0.25f, 0.2f, 0.3f}, 0.12f, 5, 2);
  return s;
}

TEST(GltfSpecular, EveryMethodAndTreeGivesTheSameBits) {
  expect_every_method_and_tree_agree(
      "specular-room", specular_room(), feature_room_camera(), feature_room_settings(),
      expect_features(SceneFeatures{.textures = true, .texcoord1 = true, .conductor = true, .dielectric = true,
                                    .plastic = true, .texture_transform = true, .specular = true}),
      any_light);
}

}  // namespace
