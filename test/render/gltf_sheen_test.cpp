// KHR_materials_sheen in the renderer (docs/bsdf.md, "Sheen"): the feature option only where a used
// material has a sheen, the textures' channels (RGB of the colour texture, A of the roughness
// texture), and the same bits from every method and tree. The Mitsuba comparison is the reference
// scene `sheen` (reference_scenes_test.cpp).
#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "method_tree_agreement.h"
#include "render_fixture.h"
#include "scene_building.h"

using namespace cohort;
using namespace cohort::test;

namespace {

// A room of grey walls lit by a small emitter, with a sphere and a floor of `floor` material.
Scene sheen_room(const SceneMaterial& floor, const SceneMaterial& ball) {
  Scene s;
  SceneMaterial grey;
  grey.base_color = glm::vec3(0.6f);
  SceneMaterial light;
  light.emission = glm::vec3(6.f);
  light.double_sided = true;
  s.materials = {grey, light, floor, ball};
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0.f);
  add_quad(s, o, z, x, 2, true);  // floor
  add_quad(s, o + y, x, z, 0, true);
  add_quad(s, o, y, z, 0, true);
  add_quad(s, o + x, z, y, 0, true);
  add_quad(s, o, x, y, 0, true);
  add_quad(s, o + z, y, x, 0, true);
  add_quad(s, glm::vec3(0.4f, 0.99f, 0.4f), 0.2f * x, 0.2f * z, 1, true);
  add_sphere(s, {0.5f, 0.3f, 0.55f}, 0.22f, 3, 2);
  s.uvs.resize(s.positions.size(), glm::vec2(0.3f, 0.6f));
  return s;
}

const SceneCamera kCamera{{0.5f, 0.5f, 0.02f}, {0.5f, 0.3f, 1.f}, {0, 1, 0}, 70};

RenderSettings small(std::uint32_t spp) {
  RenderSettings s;
  s.width = 24;
  s.height = 20;
  s.spp = spp;
  s.rr_depth = 3;
  s.seed = 7;
  return s;
}

SceneMaterial with_sheen(glm::vec3 base, glm::vec3 colour, float roughness) {
  SceneMaterial m;
  m.base_color = base;
  m.sheen.color = colour;
  m.sheen.roughness = roughness;
  return m;
}

bool same_bits(const RenderResult& a, const RenderResult& b) {
  return a.image.rgb.size() == b.image.rgb.size() &&
         std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * sizeof(float)) == 0 &&
         a.rays == b.rays;
}


}  // namespace

TEST(GltfSheen, OnlyAUsedNonZeroSheenCompilesIt) {
  SceneMaterial plain;
  const SceneMaterial velvet = with_sheen(glm::vec3(0.2f), glm::vec3(0.8f, 0.4f, 0.2f), 0.5f);
  SceneMaterial black = velvet;
  black.sheen.color = glm::vec3(0.f);  // a roughness without colour is no sheen
  EXPECT_FALSE(prepare(sheen_room(plain, plain), kCamera).tables.features.sheen);
  EXPECT_FALSE(prepare(sheen_room(black, plain), kCamera).tables.features.sheen);
  const PreparedScene p = prepare(sheen_room(plain, velvet), kCamera);
  EXPECT_TRUE(p.tables.features.sheen);
  EXPECT_EQ(p.tables.features.build_options(), "-DCOHORT_FEATURE_SHEEN");
  ASSERT_EQ(p.tables.material_sheen.size(), p.tables.materials.size());
  EXPECT_EQ(p.tables.material_sheen[3].color_roughness.x, 0.8f);
  EXPECT_EQ(p.tables.material_sheen[3].color_roughness.w, 0.5f);
  // a material no triangle uses compiles nothing, and without the feature no table goes up
  Scene unused = sheen_room(plain, plain);
  unused.materials.push_back(velvet);
  const PreparedScene q = prepare(unused, kCamera);
  EXPECT_FALSE(q.tables.features.sheen);
  EXPECT_TRUE(q.tables.material_sheen.empty());
}

// The colour texture's RGB (sRGB) and the roughness texture's A (linear) multiply the factors: white
// RGB and A 255 give the factors' image bit for bit, A 0 the image of roughness 0 (RGB ignored).
TEST(GltfSheen, TexturesMultiplyTheFactorsThroughTheirChannels) {
  const auto room = [](int colour_rgb, int rough_a, float roughness) {
    const SceneMaterial ball = with_sheen(glm::vec3(0.1f, 0.15f, 0.4f), glm::vec3(0.9f, 0.5f, 0.3f), 0.6f);
    SceneMaterial floor = ball;
    floor.sheen.roughness = roughness;
    Scene s = sheen_room(floor, ball);
    if (colour_rgb >= 0)
      s.materials[2].sheen.color_texture = add_texture(s, 2, 2, [colour_rgb](int, int) {
        const auto c = std::uint8_t(colour_rgb);
        return std::array<std::uint8_t, 4>{c, c, c, 0};
      });
    if (rough_a >= 0)
      s.materials[2].sheen.roughness_texture = add_texture(
          s, 2, 2,
          [rough_a](int, int) { return std::array<std::uint8_t, 4>{255, 255, 255, std::uint8_t(rough_a)}; },
          TextureSampler{.nearest = true}, false);
    return prepare(s, kCamera);
  };
  const RenderSettings s = small(4);
  const RenderResult factors = render_prepared(room(-1, -1, 0.6f), s);
  const PreparedScene textured = room(255, 255, 0.6f);
  EXPECT_TRUE(textured.tables.features.textures && textured.tables.features.sheen);
  EXPECT_TRUE(same_bits(render_prepared(textured, s), factors)) << "white RGB and A 255 multiply by 1";
  const RenderResult zero_roughness = render_prepared(room(-1, -1, 0.f), s);
  EXPECT_TRUE(same_bits(render_prepared(room(-1, 0, 0.6f), s), zero_roughness)) << "A 0 makes the roughness 0";
  EXPECT_FALSE(same_bits(zero_roughness, factors));
  const RenderResult no_colour = render_prepared(room(0, -1, 0.6f), s);  // black RGB: the bare base
  SceneMaterial bare;
  bare.base_color = glm::vec3(0.1f, 0.15f, 0.4f);
  SceneMaterial ball = with_sheen(glm::vec3(0.1f, 0.15f, 0.4f), glm::vec3(0.9f, 0.5f, 0.3f), 0.6f);
  const RenderResult base_floor = render_prepared(prepare(sheen_room(bare, ball), kCamera), s);
  EXPECT_TRUE(same_bits(no_colour, base_floor)) << "a black sheen colour leaves the base as it is";
}

// Every method on every tree gives naive's image on the deep KD-tree with sheen: factors on the
// sphere, and on the floor a colour texture read through TEXCOORD_1 and a KHR_texture_transform and a
// bilinear roughness texture.
TEST(GltfSheen, EveryMethodAndTreeGivesTheSameBits) {
  SceneMaterial floor = with_sheen(glm::vec3(0.2f, 0.3f, 0.6f), glm::vec3(1.f, 0.8f, 0.6f), 0.7f);
  SceneMaterial ball = with_sheen(glm::vec3(0.05f, 0.05f, 0.3f), glm::vec3(0.9f, 0.5f, 0.3f), 0.3f);
  Scene s = sheen_room(floor, ball);
  s.materials[2].sheen.color_texture = add_texture(s, 3, 3, [](int x, int y) {
    return std::array<std::uint8_t, 4>{std::uint8_t(60 + 80 * x), 200, std::uint8_t(40 + 90 * y), 255};
  });
  s.materials[2].sheen.color_texcoord = 1;
  s.materials[2].sheen.color_transform = UvTransform{{0.2f, -0.1f}, 0.4f, {1.5f, 2.f}};
  s.materials[2].sheen.roughness_texture = add_texture(
      s, 2, 2, [](int x, int y) { return std::array<std::uint8_t, 4>{0, 0, 0, std::uint8_t(40 + 100 * x + 60 * y)}; },
      TextureSampler{}, false);
  for (glm::vec2& uv : s.uvs) uv = 2.2f * uv - 0.4f;
  s.uvs1.resize(s.uvs.size());
  for (std::size_t i = 0; i < s.uvs.size(); ++i) s.uvs1[i] = glm::vec2(s.uvs[i].y, 1.2f * s.uvs[i].x);
  const int compared = expect_every_method_and_tree_agree(
      "sheen-room", s, kCamera, small(3),
      expect_features(SceneFeatures{.textures = true, .texcoord1 = true, .texture_transform = true, .sheen = true}),
      any_light);
  EXPECT_GT(compared, 5);
}

// glTF's clearcoat lies above the sheen: with both on one material the coat is chosen first and the
// sheen from the rest of u_select, and every method on every tree still gives naive's image on the
// deep KD-tree; the programs carry both features.
TEST(GltfSheen, ACoatOverASheenGivesTheSameBitsOnEveryMethodAndTree) {
  SceneMaterial floor = with_sheen(glm::vec3(0.2f, 0.3f, 0.6f), glm::vec3(1.f, 0.8f, 0.6f), 0.7f);
  floor.clearcoat.factor = 0.8f;
  floor.clearcoat.roughness = 0.3f;
  SceneMaterial ball = with_sheen(glm::vec3(0.05f, 0.05f, 0.3f), glm::vec3(0.9f, 0.5f, 0.3f), 0.3f);
  ball.clearcoat.factor = 1.f;  // a smooth coat: delta samples over the sheen
  const Scene s = sheen_room(floor, ball);
  const int compared = expect_every_method_and_tree_agree(
      "coat-over-sheen-room", s, kCamera, small(3),
      expect_features(SceneFeatures{.clearcoat = true, .sheen = true}),
      any_light);
  EXPECT_GT(compared, 5);
}
