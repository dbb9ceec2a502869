// The glTF material beyond base colour and emission (docs/bsdf.md, "Textures"): samplers against a
// brute-force reference, the metallic-roughness texture's channels, TEXCOORD_1, COLOR_0, the
// kernel features they select, and the same bits from every method and tree.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "kernels/common/shading/texture.h"
#include "method_tree_agreement.h"
#include "render_fixture.h"
#include "runtime/backend/device_support.h"
#include "runtime/render/methods/methods.h"
#include "scene_building.h"

using namespace cohort;
using namespace cohort::test;

namespace {

// ---- Samplers: texture_sample against OpenGL's rules, written out in double precision -----------

// OpenGL's integer wrap of a texel index (the specification's 8.14.2; Mitsuba's bitmap does the same).
int wrap_index(int i, int n, std::uint32_t mode) {
  if (mode == TEX_WRAP_CLAMP) return std::clamp(i, 0, n - 1);
  if (mode == TEX_WRAP_MIRROR) {
    const int t = ((i % (2 * n)) + 2 * n) % (2 * n);
    return t < n ? t : 2 * n - 1 - t;
  }
  return ((i % n) + n) % n;
}

double decode(std::uint32_t texel, int channel, bool data) {
  const std::uint32_t byte = (texel >> (8 * channel)) & 255u;
  if (data) return byte / 255.0;
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double reference_sample(const std::vector<std::uint32_t>& texels, int w, int h, std::uint32_t sampler, double u,
                        double v, int channel) {
  const bool data = sampler & TEX_DATA;
  auto at = [&](int x, int y) {
    return decode(texels[std::size_t(wrap_index(y, h, tex_wrap_t(sampler))) * w + wrap_index(x, w, tex_wrap_s(sampler))],
                  channel, data);
  };
  if (sampler & TEX_NEAREST) return at(int(std::floor(u * w)), int(std::floor(v * h)));
  const double x = u * w - 0.5, y = v * h - 0.5;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double tx = x - x0, ty = y - y0;
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) + ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

TEST(TextureSampler, EveryFilterAndWrapModeFollowsOpenGl) {
  const int w = 5, h = 3;
  std::vector<std::uint32_t> texels(w * h);
  std::mt19937 rng(7);
  for (auto& t : texels) t = rng();
  std::uniform_real_distribution<double> coordinate(-2.5, 2.5);
  for (std::uint32_t flags : {0u, TEX_NEAREST, TEX_DATA, TEX_NEAREST | TEX_DATA})
    for (std::uint32_t ws : {TEX_WRAP_REPEAT, TEX_WRAP_CLAMP, TEX_WRAP_MIRROR})
      for (std::uint32_t wt : {TEX_WRAP_REPEAT, TEX_WRAP_CLAMP, TEX_WRAP_MIRROR}) {
        const TextureDesc desc{0, w, h, tex_sampler(flags, ws, wt)};
        int checked = 0;
        while (checked < 2000) {
          const float u = float(coordinate(rng)), v = float(coordinate(rng));
          // nearest texels change at texel edges, where float and double may round apart
          const double eu = u * w - std::floor(u * w), ev = v * h - std::floor(v * h);
          if ((flags & TEX_NEAREST) && (eu < 1e-4 || eu > 1 - 1e-4 || ev < 1e-4 || ev > 1 - 1e-4)) continue;
          const co_vec3 got = texture_sample(&desc, texels.data(), 0, u, v);
          const float values[3] = {got.x, got.y, got.z};
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(values[c], reference_sample(texels, w, h, desc.sampler, u, v, c), 2e-6)
                << "flags " << flags << " wrap " << ws << "/" << wt << " at (" << u << ", " << v << ") channel " << c;
          ++checked;
        }
      }
}

TEST(TextureSampler, NearestAndBilinearDifferOnAMagnifiedChecker) {
  const std::array<std::uint32_t, 4> checker = {0xffffffffu, 0xff000000u, 0xff000000u, 0xffffffffu};
  const TextureDesc linear{0, 2, 2, 0}, nearest{0, 2, 2, TEX_NEAREST};
  EXPECT_EQ(texture_sample(&nearest, checker.data(), 0, 0.4f, 0.1f).x, 1.f);
  EXPECT_LT(texture_sample(&linear, checker.data(), 0, 0.4f, 0.1f).x, 1.f);
}

// ---- Scenes under a white sky: a Lambertian that a camera ray hits shows its albedo exactly ------

SceneCamera facing_quad() { return SceneCamera{{0.f, 0.f, 2.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 20.f}; }

RenderSettings white_sky(std::uint32_t size = 4) {
  RenderSettings rs;
  rs.width = rs.height = size;
  rs.spp = 2;
  rs.environment = glm::vec3(1.f);
  rs.max_depth = 2;
  return rs;
}

TEST(GltfMaterial, VertexColoursMultiplyTheBaseColour) {
  Scene s;
  SceneMaterial m;
  m.base_color = glm::vec3(0.5f, 1.f, 1.f);
  s.materials = {m};
  add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
  s.colors.assign(s.positions.size(), glm::vec4(0.2f, 0.5f, 0.9f, 1.f));
  const PreparedScene p = prepare(s, facing_quad());
  ASSERT_TRUE(p.tables.features.vertex_colors);
  EXPECT_NE(p.tables.features.build_options().find("-DCOHORT_FEATURE_VERTEX_COLORS"), std::string::npos);
  const RenderResult r = render_prepared(p, white_sky());
  for (std::size_t i = 0; i < r.image.rgb.size(); i += 3) {
    EXPECT_NEAR(r.image.rgb[i], 0.1f, 1e-6f);
    EXPECT_NEAR(r.image.rgb[i + 1], 0.5f, 1e-6f);
    EXPECT_NEAR(r.image.rgb[i + 2], 0.9f, 1e-6f);
  }
}

TEST(GltfMaterial, ATextureReadsTheCoordinateSetItAsksFor) {
  Scene s;
  SceneMaterial m;
  m.base_color = glm::vec3(1.f);
  // left texel red, right texel green; set 0 points at the left one, set 1 at the right one
  m.base_color_texture = add_texture(s, 2, 1, [](int x, int) {
    return x == 0 ? std::array<std::uint8_t, 4>{255, 0, 0, 255} : std::array<std::uint8_t, 4>{0, 255, 0, 255};
  });
  m.base_color_texcoord = 1;
  s.materials = {m};
  add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
  s.uvs.assign(s.positions.size(), glm::vec2(0.25f, 0.5f));
  s.uvs1.assign(s.positions.size(), glm::vec2(0.75f, 0.5f));
  const PreparedScene p = prepare(s, facing_quad());
  ASSERT_TRUE(p.tables.features.texcoord1);
  ASSERT_EQ(p.tables.triangle_uvs.size(), 2 * p.tree.triangles.size());
  const RenderResult r = render_prepared(p, white_sky());
  for (std::size_t i = 0; i < r.image.rgb.size(); i += 3) {  // bilinear, a few ulps off the texel centre
    EXPECT_NEAR(r.image.rgb[i], 0.f, 1e-6f);
    EXPECT_NEAR(r.image.rgb[i + 1], 1.f, 1e-6f);
  }
  // a scene whose textures all read set 0 compiles no second set
  Scene first = s;
  first.materials[0].base_color_texcoord = 0;
  const PreparedScene q = prepare(first, facing_quad());
  EXPECT_FALSE(q.tables.features.texcoord1);
  EXPECT_EQ(q.tables.triangle_uvs.size(), q.tree.triangles.size());
}

// Two quads side by side. `textured`: one material whose metallic-roughness texture (2 x 1 texels,
// each quad's coordinates at one texel's centre) says metal and roughness 77/255 on the left, no
// metal and roughness 1 on the right. Otherwise two untextured materials with those values.
Scene metal_where_blue_says(bool textured) {
  Scene s;
  SceneMaterial base;
  base.base_color = glm::vec3(0.9f, 0.6f, 0.3f);
  if (textured) {
    base.metallic = 1.f;
    base.roughness = 1.f;
    base.metallic_roughness_texture = add_texture(
        s, 2, 1,
        [](int x, int) {
          // R and A are not read; the sRGB decode of G or B would change the values
          return x == 0 ? std::array<std::uint8_t, 4>{9, 77, 255, 3} : std::array<std::uint8_t, 4>{200, 255, 0, 255};
        },
        TextureSampler{.nearest = true}, false);  // interpolated coordinates are a few ulps off the centres
    s.materials = {base};
  } else {
    SceneMaterial metal = base, plain = base;
    metal.metallic = 1.f;
    metal.roughness = 77 * (1.0f / 255.0f);  // as the kernel scales the factor 1 by the texel
    plain.metallic = 0.f;
    plain.roughness = 1.f;
    s.materials = {metal, plain};
  }
  add_quad(s, {-1, -1, 0}, {1, 0, 0}, {0, 2, 0}, 0, true);
  add_quad(s, {0, -1, 0}, {1, 0, 0}, {0, 2, 0}, textured ? 0 : 1, true);
  for (std::size_t i = 0; i < s.uvs.size(); ++i) s.uvs[i] = glm::vec2(i < 6 ? 0.25f : 0.75f, 0.5f);
  add_quad(s, {-3, -1, -0.5f}, {6, 0, 0}, {0, 0, 3}, textured ? 0 : 1, true);  // a floor for the metal to reflect
  for (std::size_t i = 12; i < s.uvs.size(); ++i) s.uvs[i] = glm::vec2(0.75f, 0.5f);
  return s;
}

TEST(GltfMaterial, MetallicRoughnessTextureIsBlueMetalAndGreenRoughness) {
  const SceneCamera camera{{0.f, 0.5f, 2.5f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f};
  const PreparedScene textured = prepare(metal_where_blue_says(true), camera);
  const PreparedScene factors = prepare(metal_where_blue_says(false), camera);
  ASSERT_TRUE(textured.tables.features.textures);
  RenderSettings rs = white_sky(16);
  rs.max_depth = 4;
  rs.spp = 3;
  const RenderResult a = render_prepared(textured, rs), b = render_prepared(factors, rs);
  ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
  EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * sizeof(float)))
      << "the texture's blue and green must give the factors' image bit for bit";
  EXPECT_EQ(a.rays, b.rays);
}

TEST(GltfMaterial, MetallicRoughnessTextureSelectsTheFamiliesItCanReach) {
  Material m{};
  m.metallic = 1.f;
  m.roughness = 1.f;
  m.metallic_roughness_texture = -1;
  EXPECT_EQ(material_features(m), (SceneFeatures{.conductor = true}));
  m.metallic_roughness_texture = 0;  // B < 1 reaches the dielectric base, G < 1 the plastic
  EXPECT_EQ(material_features(m), (SceneFeatures{.conductor = true, .plastic = true}));
  m.metallic = 0.f;  // a factor of 0 stays 0 whatever the texel
  EXPECT_EQ(material_features(m), (SceneFeatures{.plastic = true}));
}

// ---- Every method and tree gives the same bits with every feature above --------------------------

Scene feature_room() {
  Scene s;
  SceneMaterial white;
  white.base_color = glm::vec3(0.7f);
  SceneMaterial light;
  light.emission = glm::vec3(6.f);
  light.double_sided = true;
  SceneMaterial floor;  // metal and roughness from a nearest, mirrored texture; base colour from set 1
  floor.metallic = 1.f;
  floor.roughness = 1.f;
  floor.metallic_roughness_texture = add_texture(
      s, 4, 4,
      [](int x, int y) {
        return std::array<std::uint8_t, 4>{0, std::uint8_t(40 + 50 * y), std::uint8_t((x + y) % 2 ? 255 : 0), 255};
      },
      TextureSampler{.nearest = true, .wrap_s = TextureWrap::mirrored_repeat, .wrap_t = TextureWrap::clamp_to_edge},
      false);
  floor.base_color_texture = add_texture(s, 3, 3, [](int x, int y) {
    return std::array<std::uint8_t, 4>{std::uint8_t(80 * x + 40), 150, std::uint8_t(100 * y + 20), 255};
  });
  floor.base_color_texcoord = 1;
  floor.normal_texture = add_texture(
      s, 2, 2,
      [](int x, int y) { return std::array<std::uint8_t, 4>{std::uint8_t(90 + 80 * x), std::uint8_t(100 + 60 * y), 230, 255}; },
      TextureSampler{}, false);
  floor.normal_scale = 1.5f;
  s.materials = {white, light, floor};
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0.f);
  add_quad(s, o, z, x, 2, true);  // floor
  for (std::size_t i = 0; i < 6; ++i) s.uvs[i] = 2.5f * s.uvs[i] - 0.7f;  // beyond [0, 1]: wrap modes at work
  s.uvs1.assign(s.positions.size(), glm::vec2(0.f));
  for (std::size_t i = 0; i < 6; ++i) s.uvs1[i] = glm::vec2(s.uvs[i].y, 1.3f * s.uvs[i].x);
  s.normals.assign(6, glm::vec3(0, 1, 0));  // the floor's u runs along +z
  s.tangents.assign(6, glm::vec4(0, 0, 1, 1));
  add_quad(s, o + y, x, z, 0);  // ceiling and walls
  add_quad(s, o, y, z, 0);
  add_quad(s, o + x, z, y, 0);
  add_quad(s, o, x, y, 0);
  add_quad(s, o + z, y, x, 0);
  add_quad(s, glm::vec3(0.4f, 0.99f, 0.4f), 0.2f * x, 0.2f * z, 1);
  const std::size_t first_sphere = s.positions.size();
  add_sphere(s, {0.5f, 0.3f, 0.6f}, 0.2f, 0, 2);  // vertex colours on the sphere only
  s.colors.assign(s.positions.size(), glm::vec4(1.f));
  for (std::size_t i = first_sphere; i < s.positions.size(); ++i)
    s.colors[i] = glm::vec4(0.3f + 0.5f * s.positions[i].x, 0.9f, 0.2f + s.positions[i].y, 1.f);
  return s;
}

TEST(GltfMaterial, EveryMethodAndTreeGivesTheSameBits) {
  expect_every_method_and_tree_agree(
      "feature-room", feature_room(), feature_room_camera(), feature_room_settings(),
      expect_features(SceneFeatures{.textures = true, .texcoord1 = true, .vertex_colors = true, .normal_map = true,
                                    .conductor = true, .plastic = true}),
      any_light);
}

}  // namespace

// ---- Normal maps ---------------------------------------------------------------------------------

namespace {

// A normal map of one texel: the tangent-space normal (x, y, z) in [-1, 1], encoded as glTF stores it.
int add_normal_map(Scene& s, glm::vec3 n) {
  const glm::vec3 c = glm::round((0.5f * glm::normalize(n) + 0.5f) * 255.f);
  return add_texture(
      s, 1, 1, [c](int, int) { return std::array<std::uint8_t, 4>{std::uint8_t(c.x), std::uint8_t(c.y), std::uint8_t(c.z), 255}; },
      TextureSampler{}, false);
}

// A white Lambertian quad in the plane z = 0 facing +z, tangent +x, bitangent +y (w = 1), with the
// normal map `n`; an emitter strip at +x or -x (`light_x`) facing the quad, or below it (`below`).
Scene tilted_quad(glm::vec3 n, float light_x, bool below = false, float w = 1.f) {
  Scene s;
  SceneMaterial white;
  white.base_color = glm::vec3(0.8f);
  white.normal_texture = add_normal_map(s, n);
  SceneMaterial light;
  light.base_color = glm::vec3(0.f);
  light.emission = glm::vec3(5.f);
  light.double_sided = true;
  s.materials = {white, light};
  add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0, true);
  s.normals.assign(s.positions.size(), glm::vec3(0, 0, 1));
  s.tangents.assign(s.positions.size(), glm::vec4(1, 0, 0, w));
  if (below)
    add_quad(s, {-1, -1, -0.5f}, {2, 0, 0}, {0, 2, 0}, 1);  // faces +z, towards the quad's back
  else
    add_quad(s, {light_x, -1, 0.05f}, {0, 2, 0}, {0, 0, 1}, 1);
  return s;
}

double mean(const RenderResult& r) {
  double sum = 0;
  for (float v : r.image.rgb) sum += v;
  return sum / r.image.rgb.size();
}

RenderSettings dark_sky(std::uint32_t spp = 16) {
  RenderSettings rs;
  rs.width = rs.height = 8;
  rs.spp = spp;
  rs.max_depth = 3;
  return rs;
}

}  // namespace

TEST(NormalMap, TheMapTiltsShadingTowardsTangentAndBitangent) {
  const SceneCamera camera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f};
  const PreparedScene towards = prepare(tilted_quad({0.6f, 0, 1}, 1.2f), camera);
  ASSERT_TRUE(towards.tables.features.normal_map);
  EXPECT_NE(towards.tables.features.build_options().find("-DCOHORT_FEATURE_NORMAL_MAP"), std::string::npos);
  const double lit = mean(render_prepared(towards, dark_sky()));
  const double away = mean(render_prepared(prepare(tilted_quad({-0.6f, 0, 1}, 1.2f), camera), dark_sky()));
  Scene plain_scene = tilted_quad({0, 0, 1}, 1.2f);
  plain_scene.materials[0].normal_texture = -1;
  const double plain = mean(render_prepared(prepare(plain_scene, camera), dark_sky()));
  EXPECT_GT(lit, 1.3 * plain) << "a normal tilted towards the light (the tangent, +x) catches more of it";
  EXPECT_LT(away, 0.77 * plain);
  // the bitangent is cross(n, t) * w: +y with w = 1, -y with w = -1
  const Scene up_light = [] {
    Scene s = tilted_quad({0, 0.6f, 1}, 0.f);
    for (std::size_t i = 6; i < 12; ++i) s.positions[i] = glm::vec3(s.positions[i].y, 1.2f, s.positions[i].z);
    return s;
  }();
  Scene mirrored = up_light;
  for (glm::vec4& t : mirrored.tangents) t.w = -1.f;
  const double y_up = mean(render_prepared(prepare(up_light, camera), dark_sky()));
  const double y_down = mean(render_prepared(prepare(mirrored, camera), dark_sky()));
  EXPECT_GT(y_up, 1.3 * y_down);
}

// The shading normal never sends a ray through the surface: a quad whose map tilts the normal almost
// into its plane, lit only from behind, stays black from the front; lit from the front, it is not.
TEST(NormalMap, NoLightLeaksThroughTheSurface) {
  const SceneCamera camera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f};
  for (const glm::vec3 n : {glm::vec3(1, 0, 0.05f), glm::vec3(0, -1, 0.1f), glm::vec3(0.7f, 0.7f, 0.02f)}) {
    const RenderResult behind = render_prepared(prepare(tilted_quad(n, 0.f, true), camera), dark_sky(32));
    EXPECT_EQ(mean(behind), 0.0) << "light leaked through a quad mapped to (" << n.x << ", " << n.y << ", " << n.z << ")";
    const RenderResult front = render_prepared(prepare(tilted_quad(n, 1.2f), camera), dark_sky(32));
    EXPECT_GT(mean(front), 0.0);
  }
}

// No energy is made: a white Lambertian sphere with a bumpy normal map in the white furnace returns
// at most the sky's radiance (directions the map would send into the surface are absorbed).
TEST(NormalMap, AWhiteFurnaceStaysAtOrBelowOne) {
  Scene s;
  SceneMaterial white;
  white.base_color = glm::vec3(1.f);
  white.normal_texture = add_texture(
      s, 4, 4,
      [](int x, int y) {
        return std::array<std::uint8_t, 4>{std::uint8_t(60 * x + 30), std::uint8_t(70 * y + 20), 200, 255};
      },
      TextureSampler{.nearest = true}, false);
  s.materials = {white};
  add_sphere(s, glm::vec3(0.f), 1.f, 0, 3);
  s.uvs.resize(s.positions.size());
  s.normals.resize(s.positions.size());
  s.tangents.resize(s.positions.size());
  for (std::size_t i = 0; i < s.positions.size(); ++i) {
    const glm::vec3 p = s.positions[i];
    s.uvs[i] = glm::vec2(2.f * p.x + 0.3f, 2.f * p.y + 0.1f);
    s.normals[i] = glm::normalize(p);
    const glm::vec3 t = glm::cross(glm::vec3(0, 1, 0), p);
    s.tangents[i] = glm::length(t) > 1e-3f ? glm::vec4(glm::normalize(t), 1.f) : glm::vec4(1, 0, 0, 1);
  }
  const PreparedScene p = prepare(s, SceneCamera{{0.f, 0.f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 30.f});
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.spp = 64;
  rs.environment = glm::vec3(1.f);
  const RenderResult r = render_prepared(p, rs);
  const PixelStats all = channel_stats(r.image, 1);
  EXPECT_LT(all.mean, 1.0 + 5 * all.standard_error) << "energy made";
  EXPECT_GT(all.mean, 0.8) << "far more absorbed than a bumpy map explains";
}

// Against closed forms, for one constant tilted normal n_s at angle theta from the surface's normal.
// Under a white sky (two segments) a white-ish Lambertian returns albedo times the share of its cosine
// lobe about n_s that lies above the surface, (1 + cos theta) / 2: the absorbed rest is rule (2) of
// docs/bsdf.md. Lit by a point light alone, it returns albedo / pi * I * max(0, n_s . l) / r^2.
TEST(NormalMap, AConstantTiltMatchesClosedForms) {
  const glm::vec3 tilt = glm::normalize(glm::vec3(0.5f, 0.3f, 1.f));
  Scene s = tilted_quad(tilt, 0.f);
  s.positions.resize(6);  // the quad alone
  s.material_ids.resize(2);
  s.uvs.resize(6);
  s.normals.resize(6);
  s.tangents.resize(6);
  s.materials[0].base_color = glm::vec3(0.5f);
  // the texel the map stores, decoded as the kernel decodes it
  const glm::vec3 c = glm::round((0.5f * tilt + 0.5f) * 255.f) / 255.f * 2.f - 1.f;
  const glm::vec3 ns = glm::normalize(c);
  const SceneCamera camera{{0.f, 0.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 2.f};

  RenderSettings sky;
  sky.width = sky.height = 8;
  sky.spp = 4096;
  sky.environment = glm::vec3(1.f);
  sky.max_depth = 2;
  const RenderResult r = render_prepared(prepare(s, camera), sky);
  const PixelStats stats = channel_stats(r.image, 0);
  const double expected = 0.5 * (1.0 + ns.z) / 2.0;
  EXPECT_NEAR(stats.mean, expected, 5 * stats.standard_error + 1e-4) << "flat would be 0.5";

  SceneLight point;
  point.position = glm::vec3(1.f, 2.f, 3.f);
  point.intensity = glm::vec3(10.f);
  s.lights = {point};
  RenderSettings lit;
  lit.width = lit.height = 4;
  lit.spp = 16;
  lit.max_depth = 2;
  const RenderResult direct = render_prepared(prepare(s, camera), lit);
  const glm::vec3 l = point.position;
  const double analytic = 0.5 / M_PI * 10.0 * glm::dot(ns, glm::normalize(l)) / glm::dot(l, l);
  EXPECT_NEAR(channel_stats(direct.image, 0).mean, analytic, 2e-3 * analytic) << "flat: "
      << 0.5 / M_PI * 10.0 * glm::normalize(l).z / glm::dot(l, l);
}
