// glTF KHR_materials_clearcoat in the path tracer (docs/bsdf.md, "Clearcoat"): the kernel feature it
// selects, its textures against the factors they scale, energy under a white sky, and the same bits
// from every method and tree. The Mitsuba comparison is the reference scene `clearcoat`
// (reference_scenes_test.cpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "method_tree_agreement.h"
#include "render_fixture.h"
#include "scene_building.h"

using namespace cohort;
using namespace cohort::test;

namespace {

SceneMaterial lambertian(glm::vec3 albedo) {
  SceneMaterial m;
  m.base_color = albedo;
  return m;
}

TEST(GltfClearcoat, OnlyAUsedCoatOfNonZeroFactorSelectsTheFeature) {
  const SceneCamera camera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 40.f};
  SceneMaterial plain = lambertian(glm::vec3(0.7f));
  SceneMaterial unused = plain;
  unused.clearcoat.factor = 1.f;
  SceneMaterial zero = plain;  // a coat of factor 0, with a texture that could not raise it
  zero.clearcoat.roughness = 0.5f;
  Scene s;
  zero.clearcoat.texture = add_texture(s, 1, 1, [](int, int) { return std::array<std::uint8_t, 4>{255, 255, 255, 255}; },
                                       TextureSampler{}, false);
  s.materials = {plain, unused, zero};
  add_quad(s, {-1, -1, 0}, {1, 0, 0}, {0, 2, 0}, 0, true);
  add_quad(s, {0, -1, 0}, {1, 0, 0}, {0, 2, 0}, 2, true);
  const PreparedScene none = prepare(s, camera);
  EXPECT_EQ(none.tables.features, SceneFeatures{}) << "no coat: no texture uploaded, no option";
  EXPECT_TRUE(none.tables.material_coats.empty());
  EXPECT_TRUE(none.tables.textures.empty());

  s.materials[2].clearcoat.factor = 0.5f;
  const PreparedScene coated = prepare(s, camera);
  EXPECT_EQ(coated.tables.features, (SceneFeatures{.textures = true, .clearcoat = true}));
  ASSERT_EQ(coated.tables.material_coats.size(), 3u);  // one entry per material
  EXPECT_EQ(coated.tables.material_coats[2].factor, 0.5f);
  EXPECT_EQ(coated.tables.material_coats[2].factor_texture, 0);
  EXPECT_EQ(coated.tables.material_coats[1].factor_texture, -1);

  // a coat's normal map needs the tangent frames: the normal-map option comes with it
  s.materials[2].clearcoat.normal_texture = s.materials[2].clearcoat.texture;
  EXPECT_TRUE(prepare(s, camera).tables.features.normal_map);
}

// A smooth coat over a white Lambertian sphere under a white sky: the coat is picked with
// probability c F and weighs c / q times F, the base weighs 1, so every sample is 1 (to rounding),
// whatever the factor. A rough coat stays at 1 up to its albedo's small excess over F (at most 6e-4)
// and loses its single-scattering shadowing.
TEST(GltfClearcoat, AWhiteFurnaceStaysAtOne) {
  const SceneCamera camera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f};
  for (float roughness : {0.f, 0.3f, 0.8f})
    for (float factor : {0.4f, 1.f}) {
      Scene s;
      SceneMaterial m = lambertian(glm::vec3(1.f));
      m.clearcoat.factor = factor;
      m.clearcoat.roughness = roughness;
      s.materials = {m};
      add_sphere(s, {0.f, 0.f, 0.f}, 0.6f, 0, 3);
      const PreparedScene p = prepare(s, camera);
      ASSERT_TRUE(p.tables.features.clearcoat);
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
        EXPECT_NEAR(lo, 1.0, 1e-5) << "factor " << factor;
        EXPECT_NEAR(hi, 1.0, 1e-5) << "factor " << factor;
      } else {
        // one sample may weigh more than 1 (F at the microfacet over F about the normal); the mean may not
        // (+ 1e-3: a rough coat's albedo passes F(cos_i) by up to 6e-4, BsdfFurnace.ClearcoatOverWhite...)
        EXPECT_LE(mean, 1.0 + 5.0 * sigma + 1e-3) << "roughness " << roughness << " factor " << factor;
        EXPECT_GT(mean, 0.9) << "roughness " << roughness << " factor " << factor;  // the loss is small
      }
    }
}

// Two quads side by side. `textured`: one coat whose factor (R) and roughness (G) textures (2 x 1
// texels, nearest, each quad's coordinates at one texel's centre) say factor 77/255 and roughness
// 200/255 on the left, factor 1 and roughness 0 on the right; otherwise two coats with those
// factors. The same image bit for bit.
Scene coat_where_texture_says(bool textured) {
  Scene s;
  SceneMaterial base;
  base.base_color = glm::vec3(0.9f, 0.3f, 0.2f);
  base.metallic = 0.f;
  base.roughness = 1.f;
  const auto texel = [](int x, int) {
    // B and A are not read; the sRGB decode of R or G would change the values
    return x == 0 ? std::array<std::uint8_t, 4>{77, 200, 9, 3} : std::array<std::uint8_t, 4>{255, 0, 100, 255};
  };
  if (textured) {
    base.clearcoat.factor = 1.f;
    base.clearcoat.roughness = 1.f;
    base.clearcoat.texture = add_texture(s, 2, 1, texel, TextureSampler{.nearest = true}, false);
    base.clearcoat.roughness_texture = base.clearcoat.texture;
    s.materials = {base};
  } else {
    SceneMaterial left = base, right = base;
    left.clearcoat.factor = 77 * (1.0f / 255.0f);  // as the kernel scales the factor 1 by the texel
    left.clearcoat.roughness = 200 * (1.0f / 255.0f);
    right.clearcoat.factor = 1.f;
    right.clearcoat.roughness = 0.f;
    s.materials = {left, right};
  }
  add_quad(s, {-1, -1, 0}, {1, 0, 0}, {0, 2, 0}, 0, true);
  add_quad(s, {0, -1, 0}, {1, 0, 0}, {0, 2, 0}, textured ? 0 : 1, true);
  for (std::size_t i = 0; i < s.uvs.size(); ++i) s.uvs[i] = glm::vec2(i < 6 ? 0.25f : 0.75f, 0.5f);
  add_quad(s, {-3, -1, -0.5f}, {6, 0, 0}, {0, 0, 3}, textured ? 0 : 1, true);  // a floor for the coats to reflect
  for (std::size_t i = 12; i < s.uvs.size(); ++i) s.uvs[i] = glm::vec2(0.75f, 0.5f);
  return s;
}

TEST(GltfClearcoat, FactorAndRoughnessTexturesAreRedAndGreen) {
  const SceneCamera camera{{0.f, 0.5f, 2.5f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f};
  const PreparedScene textured = prepare(coat_where_texture_says(true), camera);
  const PreparedScene factors = prepare(coat_where_texture_says(false), camera);
  ASSERT_TRUE(textured.tables.features.textures);
  ASSERT_TRUE(textured.tables.features.clearcoat);
  RenderSettings rs = unbounded_white_sky(16, 3);
  rs.max_depth = 4;
  const RenderResult a = render_prepared(textured, rs), b = render_prepared(factors, rs);
  ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
  EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * sizeof(float)))
      << "the texture's red and green must give the factors' image bit for bit";
  EXPECT_EQ(a.rays, b.rays);
  // and the coat is there: without it the image differs
  Scene bare = coat_where_texture_says(false);
  for (SceneMaterial& m : bare.materials) m.clearcoat = SceneClearcoat{};
  const RenderResult c = render_prepared(prepare(bare, camera), rs);
  EXPECT_NE(0, std::memcmp(a.image.rgb.data(), c.image.rgb.data(), a.image.rgb.size() * sizeof(float)));
}

// ---- Every method and tree gives the same bits with clearcoat ------------------------------------

// A closed room: a smooth coat over a Lambertian sphere, a rough coat over a rough metal wall, and
// a floor whose coat takes factor, roughness and normals from textures (set 1, a transform) over a
// textured plastic; an area light in the ceiling.
Scene coat_room() {
  Scene s;
  SceneMaterial white = lambertian(glm::vec3(0.7f));
  SceneMaterial light;
  light.emission = glm::vec3(6.f);
  light.double_sided = true;
  SceneMaterial sphere = lambertian(glm::vec3(0.8f, 0.2f, 0.1f));
  sphere.clearcoat.factor = 1.f;
  SceneMaterial metal;
  metal.base_color = glm::vec3(0.9f);
  metal.metallic = 1.f;
  metal.roughness = 0.4f;
  metal.clearcoat.factor = 0.8f;
  metal.clearcoat.roughness = 0.3f;
  SceneMaterial floor;
  floor.base_color = glm::vec3(0.3f, 0.6f, 0.4f);
  floor.roughness = 0.5f;
  floor.clearcoat.factor = 1.f;
  floor.clearcoat.roughness = 0.6f;
  floor.clearcoat.texture = add_texture(
      s, 4, 4, [](int x, int y) { return std::array<std::uint8_t, 4>{std::uint8_t((x + y) % 2 ? 255 : 60), 0, 0, 255}; },
      TextureSampler{.nearest = true, .wrap_s = TextureWrap::mirrored_repeat}, false);
  floor.clearcoat.texcoord = 1;
  floor.clearcoat.roughness_texture = add_texture(
      s, 3, 3, [](int x, int y) { return std::array<std::uint8_t, 4>{0, std::uint8_t(40 * x + 60 * y), 0, 255}; },
      TextureSampler{}, false);
  floor.clearcoat.roughness_transform = UvTransform{.offset = {0.2f, 0.1f}, .rotation = 0.3f, .scale = {1.5f, 0.8f}};
  floor.clearcoat.normal_texture = add_texture(
      s, 2, 2,
      [](int x, int y) { return std::array<std::uint8_t, 4>{std::uint8_t(90 + 80 * x), std::uint8_t(100 + 60 * y), 230, 255}; },
      TextureSampler{}, false);
  floor.clearcoat.normal_scale = 1.5f;
  s.materials = {white, light, sphere, metal, floor};
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0.f);
  add_quad(s, o, z, x, 4, true);  // floor
  for (std::size_t i = 0; i < 6; ++i) s.uvs[i] = 2.5f * s.uvs[i] - 0.7f;
  s.uvs1.assign(s.positions.size(), glm::vec2(0.f));
  for (std::size_t i = 0; i < 6; ++i) s.uvs1[i] = glm::vec2(s.uvs[i].y, 1.3f * s.uvs[i].x);
  s.normals.assign(6, glm::vec3(0, 1, 0));  // the floor's u runs along +z
  s.tangents.assign(6, glm::vec4(0, 0, 1, 1));
  add_quad(s, o + y, x, z, 0);  // ceiling and walls, one of them the coated metal
  add_quad(s, o, y, z, 3);
  add_quad(s, o + x, z, y, 0);
  add_quad(s, o, x, y, 0);
  add_quad(s, o + z, y, x, 0);
  add_quad(s, glm::vec3(0.4f, 0.99f, 0.4f), 0.2f * x, 0.2f * z, 1);
  add_sphere(s, {0.5f, 0.3f, 0.6f}, 0.2f, 2, 2);
  return s;
}

TEST(GltfClearcoat, EveryMethodAndTreeGivesTheSameBits) {
  expect_every_method_and_tree_agree(
      "clearcoat-room", coat_room(), feature_room_camera(), feature_room_settings(),
      expect_features(SceneFeatures{.textures = true, .texcoord1 = true, .normal_map = true, .conductor = true,
                                    .plastic = true, .texture_transform = true, .clearcoat = true}),
      any_light);
}

}  // namespace
