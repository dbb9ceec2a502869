// glTF alphaMode (kernels/common/accel/alpha.h): MASK cuts surfaces out for camera, bounce and
// shadow rays, BLEND is stochastic transparency that converges to the mix of the scene with and
// without the surface, OPAQUE never reads alpha, and every method and tree gives the same bits with
// both. Also KHR_texture_transform, which the alpha lookups share with the colour's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "method_tree_agreement.h"
#include "render_fixture.h"
#include "runtime/backend/device_support.h"
#include "runtime/render/methods/methods.h"
#include "scene_building.h"

using namespace cohort;
using namespace cohort::test;

namespace {

// A texture of alphas.size() x 1 white texels with those alphas.
int alpha_texture(Scene& s, const std::vector<std::uint8_t>& alphas, bool nearest = true) {
  return add_texture(
      s, int(alphas.size()), 1,
      [&](int x, int) { return std::array<std::uint8_t, 4>{255, 255, 255, alphas[std::size_t(x)]}; },
      TextureSampler{.nearest = nearest});
}

SceneMaterial with_alpha(SceneMaterial m, AlphaMode mode, float cutoff = 0.5f) {
  m.alpha_mode = mode;
  m.alpha_cutoff = cutoff;
  return m;
}

// ---- Camera rays: a quad that fills the view under a white sky, emitters seen directly only ------

const SceneCamera kFacingQuad{{0.f, 0.f, 2.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 20.f};

RenderSettings sky_seen_directly(std::uint32_t size, std::uint32_t spp) {
  RenderSettings rs;
  rs.width = rs.height = size;
  rs.spp = spp;
  rs.environment = glm::vec3(1.f);
  rs.max_depth = 1;  // a camera ray that escapes sees 1, one that stops on the quad sees 0
  return rs;
}

// The quad (-1..1)^2 at z = 0 with a 2 x 1 nearest texture: alpha 0 where u < 0.5 (x < 0), 255 beyond.
Scene half_cut_quad(AlphaMode mode, float cutoff = 0.5f) {
  Scene s;
  SceneMaterial m;
  m.base_color_texture = alpha_texture(s, {0, 255});
  s.materials = {with_alpha(m, mode, cutoff)};
  add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0, true);
  return s;
}

// Pixels (all channels) that are exactly 1 and exactly 0, outside the two middle columns, where the
// cut (x = 0) falls between pixels.
struct Split {
  int ones = 0, zeros = 0, other = 0;
};
Split split(const Image& image) {
  Split out;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (x == image.width / 2 - 1 || x == image.width / 2) continue;
      const float* p = image.pixel(x, y);
      if (p[0] == 1.f && p[1] == 1.f && p[2] == 1.f)
        ++out.ones;
      else if (p[0] == 0.f && p[1] == 0.f && p[2] == 0.f)
        ++out.zeros;
      else
        ++out.other;
    }
  return out;
}

TEST(GltfAlpha, CameraRaysSeeThroughACutOut) {
  const RenderSettings rs = sky_seen_directly(16, 4);
  const PreparedScene mask = prepare(half_cut_quad(AlphaMode::mask), kFacingQuad);
  ASSERT_TRUE(mask.tables.features.alpha);
  EXPECT_NE(mask.tables.features.build_options().find("-DCOHORT_FEATURE_ALPHA"), std::string::npos);
  const Split cut = split(render_prepared(mask, rs).image);
  EXPECT_EQ(cut.other, 0);
  EXPECT_EQ(cut.ones, cut.zeros) << "the half with alpha 0 shows the sky, the other half the quad";
  EXPECT_EQ(cut.ones, 16 * 7);
  // a cutoff of 0 keeps alpha 0; above 1 cuts out even alpha 1 (glTF 2.0)
  EXPECT_EQ(split(render_prepared(prepare(half_cut_quad(AlphaMode::mask, 0.f), kFacingQuad), rs).image).zeros, 16 * 14);
  EXPECT_EQ(split(render_prepared(prepare(half_cut_quad(AlphaMode::mask, 1.5f), kFacingQuad), rs).image).ones, 16 * 14);
  // OPAQUE never reads alpha, and compiles no alpha test
  const PreparedScene opaque = prepare(half_cut_quad(AlphaMode::opaque), kFacingQuad);
  EXPECT_FALSE(opaque.tables.features.alpha);
  EXPECT_EQ(opaque.tables.features.build_options().find("ALPHA"), std::string::npos);
  EXPECT_EQ(split(render_prepared(opaque, rs).image).zeros, 16 * 14);
}

TEST(GltfAlpha, CameraRaysPassABlendSurfaceWithProbabilityOneMinusAlpha) {
  for (const float alpha : {0.25f, 0.5f}) {
    Scene s;
    SceneMaterial m;
    m.alpha = alpha;
    s.materials = {with_alpha(m, AlphaMode::blend)};
    add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
    const RenderSettings rs = sky_seen_directly(16, 64);
    const Image image = render_prepared(prepare(s, kFacingQuad), rs).image;
    // each sample passes or not: a binomial share of 16 x 16 x 64 samples
    const double samples = 16.0 * 16.0 * 64.0;
    const double standard_error = std::sqrt(alpha * (1.0 - alpha) / samples);
    EXPECT_NEAR(mean_of(image), 1.0 - alpha, 5 * standard_error) << "alpha " << alpha;
  }
}

// OPAQUE ignores a texture's alpha: the same bits as the texture with alpha 255.
TEST(GltfAlpha, OpaqueIgnoresTheTexturesAlpha) {
  const auto quad = [](std::uint8_t a) {
    Scene s;
    SceneMaterial m;
    m.alpha = 0.f;  // the factor is ignored too
    m.base_color_texture = add_texture(s, 2, 2, [a](int x, int y) {
      return std::array<std::uint8_t, 4>{std::uint8_t(60 + 100 * x), 120, std::uint8_t(200 - 90 * y), a};
    });
    s.materials = {m};
    add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0, true);
    add_quad(s, {-3, -1, -1}, {6, 0, 0}, {0, 0, 3}, 0, true);  // a floor for bounces
    return s;
  };
  const SceneCamera camera{{0.f, 0.5f, 2.5f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 45.f};
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.spp = 4;
  rs.environment = glm::vec3(1.f);
  rs.max_depth = 4;
  const PreparedScene clear = prepare(quad(0), camera), solid = prepare(quad(255), camera);
  EXPECT_FALSE(clear.tables.features.alpha);
  EXPECT_EQ(clear.tables.features.build_options(), solid.tables.features.build_options());
  const RenderResult a = render_prepared(clear, rs), b = render_prepared(solid, rs);
  ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
  EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * sizeof(float)));
  EXPECT_GT(mean_of(a.image), 0.1);
}

// ---- Shadow rays: a point light above a half-cut panel, the floor seen from under the panel ------

// Floor y = 0, the panel (-1..1)^2 at y = 1.5 (cut where x < 0 when masked), the point light at
// (0, 3, 0): the panel's shadow covers x, z in (-2, 2), its kept half x > 0. The camera at height 1,
// below the panel, looks straight down at (-1..1)^2 of the floor, so its rays never meet the panel.
Scene shadow_scene(bool panel, AlphaMode mode, bool half_geometry = false) {
  Scene s;
  SceneMaterial floor;
  floor.base_color = glm::vec3(0.6f);
  SceneMaterial cover;
  cover.base_color_texture = alpha_texture(s, {0, 255});
  s.materials = {floor, with_alpha(cover, mode)};
  add_quad(s, {-4, 0, 4}, {8, 0, 0}, {0, 0, -8}, 0, true);
  if (panel) {
    if (half_geometry)
      add_quad(s, {0, 1.5f, -1}, {1, 0, 0}, {0, 0, 2}, 1, true);  // only the kept half, opaque
    else
      add_quad(s, {-1, 1.5f, -1}, {2, 0, 0}, {0, 0, 2}, 1, true);
  }
  SceneLight light;
  light.position = glm::vec3(0.f, 3.f, 0.f);
  light.intensity = glm::vec3(20.f);
  s.lights = {light};
  return s;
}

const SceneCamera kUnderThePanel{{0.f, 1.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, 90.f};

RenderSettings direct_light(std::uint32_t spp = 4) {
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.spp = spp;
  rs.max_depth = 2;  // direct light only: a point light lights a floor point exactly or not at all
  return rs;
}

TEST(GltfAlpha, ShadowRaysPassThroughACutOut) {
  const RenderSettings rs = direct_light();
  const Image open = render_prepared(prepare(shadow_scene(false, AlphaMode::opaque), kUnderThePanel), rs).image;
  const Image masked = render_prepared(prepare(shadow_scene(true, AlphaMode::mask), kUnderThePanel), rs).image;
  const Image solid = render_prepared(prepare(shadow_scene(true, AlphaMode::opaque), kUnderThePanel), rs).image;
  const Image half = render_prepared(prepare(shadow_scene(true, AlphaMode::opaque, true), kUnderThePanel), rs).image;
  int lit = 0, dark = 0;
  for (int y = 0; y < open.height; ++y)
    for (int x = 0; x < open.width; ++x) {
      ASSERT_GT(open.pixel(x, y)[0], 0.f) << "the floor is lit everywhere without the panel";
      EXPECT_EQ(solid.pixel(x, y)[0], 0.f) << "an OPAQUE panel shadows the whole view, whatever its texture's alpha";
      if (x == open.width / 2 - 1 || x == open.width / 2) continue;  // the shadow's edge at x = 0
      // a floor sample is lit exactly as without the panel (the same hit, the same light sample),
      // or not at all; and exactly as with only the kept half there
      const bool same = std::memcmp(masked.pixel(x, y), open.pixel(x, y), 3 * sizeof(float)) == 0;
      const bool black = masked.pixel(x, y)[0] == 0.f && masked.pixel(x, y)[1] == 0.f && masked.pixel(x, y)[2] == 0.f;
      EXPECT_TRUE(same || black) << "pixel (" << x << ", " << y << ")";
      lit += same;
      dark += black;
      EXPECT_EQ(masked.pixel(x, y)[0] == 0.f, half.pixel(x, y)[0] == 0.f) << "pixel (" << x << ", " << y << ")";
    }
  EXPECT_EQ(lit, 16 * 7) << "light through the cut-out half";
  EXPECT_EQ(dark, 16 * 7) << "shadow of the kept half";
}

// ---- BLEND converges to the mix of the scene with and without the surface ------------------------

// The floor under a panel (BLEND with alpha 0.5, or opaque, or absent) and an area light above it;
// the camera below the panel sees the floor only, so each path meets the panel at most once (its
// shadow ray or its bounce towards the light): its expectation is exactly alpha times the scene with
// the panel plus (1 - alpha) times the scene without it.
Scene blend_scene(int panel /* 0 none, 1 opaque, 2 BLEND 0.5 from factor and texture */) {
  Scene s;
  SceneMaterial floor;
  floor.base_color = glm::vec3(0.7f, 0.6f, 0.5f);
  SceneMaterial cover;
  cover.base_color = glm::vec3(0.2f, 0.5f, 0.9f);
  SceneMaterial light;
  light.base_color = glm::vec3(0.f);
  light.emission = glm::vec3(8.f);
  light.double_sided = true;
  if (panel == 2) {
    cover.alpha = 0.8f;  // 0.8 x 160 / 255 = 0.50196 from the texture
    cover.base_color_texture = alpha_texture(s, {160, 160});
    cover = with_alpha(cover, AlphaMode::blend);
  }
  s.materials = {floor, cover, light};
  add_quad(s, {-4, 0, 4}, {8, 0, 0}, {0, 0, -8}, 0, true);
  if (panel) add_quad(s, {-1.2f, 1.5f, -1.2f}, {2.4f, 0, 0}, {0, 0, 2.4f}, 1, true);
  add_quad(s, {-0.5f, 3.f, -0.5f}, {1, 0, 0}, {0, 0, 1}, 2, true);
  return s;
}

TEST(GltfAlpha, BlendConvergesToTheMixOfTheSceneWithAndWithoutTheSurface) {
  RenderSettings rs;
  rs.width = rs.height = 64;
  rs.spp = 48;
  rs.max_depth = 2;
  const double alpha = 0.8 * 160.0 / 255.0;
  const Image none = render_prepared(prepare(blend_scene(0), kUnderThePanel), rs).image;
  const Image opaque = render_prepared(prepare(blend_scene(1), kUnderThePanel), rs).image;
  rs.seed = 7;  // independent of the two above
  const Image blend = render_prepared(prepare(blend_scene(2), kUnderThePanel), rs).image;
  Image mix = none;
  for (std::size_t i = 0; i < mix.rgb.size(); ++i)
    mix.rgb[i] = float(alpha * opaque.rgb[i] + (1 - alpha) * none.rgb[i]);
  EXPECT_GT(mean_of(none), 1.3 * mean_of(opaque)) << "the panel must cast a shadow for this to prove anything";
  expect_same_expectation(blend, mix, "BLEND 0.502 against the mix");
  const PixelStats b = channel_stats(blend, 1), m = channel_stats(mix, 1);
  std::printf("BLEND mean %.5f +- %.5f, mix of the scenes %.5f +- %.5f\n", b.mean, b.standard_error, m.mean,
              m.standard_error);
}

// A cut-out emitter emits only where it is kept: next-event estimation weighs its samples by the
// cover (a sample on the cut-out half adds nothing), so the floor it lights and the emitter seen
// directly match an emitter of only the kept half.
TEST(GltfAlpha, ACutOutEmitterLightsOnlyWhereItIsKept) {
  const auto lamp = [](bool half_geometry) {
    Scene s;
    SceneMaterial floor;
    floor.base_color = glm::vec3(0.7f);
    SceneMaterial light;
    light.base_color = glm::vec3(0.f);
    light.emission = glm::vec3(6.f);
    light.double_sided = true;
    light.base_color_texture = alpha_texture(s, {0, 255});
    s.materials = {floor, with_alpha(light, half_geometry ? AlphaMode::opaque : AlphaMode::mask)};
    add_quad(s, {-4, 0, 4}, {8, 0, 0}, {0, 0, -8}, 0, true);
    if (half_geometry)
      add_quad(s, {0, 2.f, -1}, {1, 0, 0}, {0, 0, 2}, 1, true);
    else
      add_quad(s, {-1, 2.f, -1}, {2, 0, 0}, {0, 0, 2}, 1, true);
    return s;
  };
  const SceneCamera camera{{0.f, 1.f, 3.5f}, {0.f, 1.f, 0.f}, {0.f, 1.f, 0.f}, 70.f};
  RenderSettings rs;
  rs.width = rs.height = 64;
  rs.spp = 32;
  rs.max_depth = 3;
  const Image half = render_prepared(prepare(lamp(true), camera), rs).image;
  rs.seed = 3;
  const Image masked = render_prepared(prepare(lamp(false), camera), rs).image;
  expect_same_expectation(masked, half, "a masked emitter against its kept half");
}

// ---- Every method and tree gives the same bits with MASK and BLEND ------------------------------

// A closed room lit from the ceiling, with a MASK panel (bilinear alpha texture and COLOR_0 alpha),
// a BLEND panel (factor times texture) and a BLEND emitter: camera, bounce and shadow rays all meet
// cut-outs and blended surfaces.
Scene alpha_room() {
  Scene s;
  SceneMaterial white;
  white.base_color = glm::vec3(0.7f);
  SceneMaterial light;
  light.emission = glm::vec3(6.f);
  light.double_sided = true;
  SceneMaterial leaves;  // MASK: a bilinear 4 x 1 alpha ramp
  leaves.base_color = glm::vec3(0.3f, 0.8f, 0.3f);
  leaves.base_color_texture = alpha_texture(s, {0, 90, 170, 255}, false);
  leaves.base_color_transform = UvTransform{{0.1f, 0.05f}, 0.3f, {1.2f, 0.9f}};  // KHR_texture_transform
  SceneMaterial glass;  // BLEND: factor 0.7 times a 2 x 1 texture
  glass.base_color = glm::vec3(0.8f, 0.4f, 0.2f);
  glass.alpha = 0.7f;
  glass.metallic = 0.5f;
  glass.roughness = 0.4f;
  glass.base_color_texture = alpha_texture(s, {60, 230});
  SceneMaterial lamp = light;  // a BLEND emitter
  lamp.emission = glm::vec3(3.f, 2.f, 1.f);
  lamp.alpha = 0.6f;
  s.materials = {white, light, with_alpha(leaves, AlphaMode::mask, 0.4f), with_alpha(glass, AlphaMode::blend),
                 with_alpha(lamp, AlphaMode::blend)};
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0.f);
  add_quad(s, o, z, x, 0, true);  // floor, ceiling and walls
  add_quad(s, o + y, x, z, 0, true);
  add_quad(s, o, y, z, 0, true);
  add_quad(s, o + x, z, y, 0, true);
  add_quad(s, o, x, y, 0, true);
  add_quad(s, o + z, y, x, 0, true);
  add_quad(s, glm::vec3(0.35f, 0.99f, 0.35f), 0.3f * x, 0.3f * z, 1, true);
  add_quad(s, glm::vec3(0.1f, 0.05f, 0.5f), 0.8f * x, 0.8f * y, 2, true);  // the masked panel across the room
  add_quad(s, glm::vec3(0.2f, 0.1f, 0.3f), 0.5f * z, 0.6f * y, 3, true);   // the blended panel
  add_quad(s, glm::vec3(0.7f, 0.6f, 0.8f), 0.2f * x, 0.2f * y, 4, true);   // the blended lamp
  for (std::size_t i = 36; i < s.uvs.size(); ++i) s.uvs[i] = 1.3f * s.uvs[i] - 0.1f;  // wrap at the edges
  s.colors.assign(s.positions.size(), glm::vec4(1.f));
  for (std::size_t i = 42; i < 48; ++i) s.colors[i].w = s.positions[i].y > 0.5f ? 0.6f : 1.f;  // COLOR_0 alpha
  return s;
}

TEST(GltfAlpha, EveryMethodAndTreeGivesTheSameBits) {
  RenderSettings s;
  s.width = 24;
  s.height = 20;
  s.spp = 3;
  s.rr_depth = 3;
  s.seed = 9;
  s.sort.sort_from_bounce = 1;  // hash and pth sort the camera rays too
  // the ray's alpha seed travels in its origin's w: through the gathered payload, the resumed and the
  // speculative walks, and small pools that refill
  expect_every_method_and_tree_agree(
      "alpha-room", alpha_room(), {{0.5f, 0.5f, 0.02f}, {0.5f, 0.4f, 1.f}, {0, 1, 0}, 75}, s,
      [](const PreparedScene& p, const char* tree) {
        ASSERT_TRUE(p.tables.features.alpha) << tree;
        ASSERT_TRUE(p.tables.features.texture_transform) << tree;
      },
      [](const Image& image) { return mean_of(image) > 0.01; });
}

}  // namespace

// ---- KHR_texture_transform ----------------------------------------------------------------------

namespace {

// A white-sky quad facing the camera whose base colour texture (4 x 1 texels, NEAREST) is read
// through `x`, or (`baked`) through coordinates the host transformed per vertex with the same affine map.
Scene transformed_quad(const UvTransform& x, bool baked) {
  Scene s;
  SceneMaterial m;
  m.base_color_texture = add_texture(
      s, 4, 1,
      [](int i, int) {
        const std::array<std::array<std::uint8_t, 4>, 4> c = {
            {{200, 40, 40, 255}, {40, 200, 40, 255}, {40, 40, 200, 255}, {200, 200, 40, 255}}};
        return c[std::size_t(i)];
      },
      TextureSampler{.nearest = true});
  if (!baked) m.base_color_transform = x;
  s.materials = {m};
  add_quad(s, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0, true);
  if (baked) {
    const float c = std::cos(x.rotation), sn = std::sin(x.rotation);
    for (glm::vec2& uv : s.uvs)
      uv = glm::vec2(c * x.scale.x * uv.x + sn * x.scale.y * uv.y + x.offset.x,
                     -sn * x.scale.x * uv.x + c * x.scale.y * uv.y + x.offset.y);
  }
  return s;
}

}  // namespace

TEST(TextureTransform, MapsCoordinatesAsGltfSaysOnlyWhereAsked) {
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.spp = 2;
  rs.environment = glm::vec3(1.f);
  rs.max_depth = 2;
  for (const UvTransform& x : {UvTransform{{0.25f, 0.f}, 0.f, {0.5f, 1.f}}, UvTransform{{0.1f, 0.3f}, 1.1f, {1.7f, 0.6f}},
                               UvTransform{{-0.35f, 2.f}, -0.4f, {-1.f, 3.f}}}) {
    const PreparedScene transformed = prepare(transformed_quad(x, false), kFacingQuad);
    ASSERT_TRUE(transformed.tables.features.texture_transform);
    EXPECT_NE(transformed.tables.features.build_options().find("-DCOHORT_FEATURE_TEXTURE_TRANSFORM"), std::string::npos);
    const PreparedScene baked = prepare(transformed_quad(x, true), kFacingQuad);
    EXPECT_FALSE(baked.tables.features.texture_transform);
    const Image a = render_prepared(transformed, rs).image, b = render_prepared(baked, rs).image;
    // nearest texels: the same texel everywhere but within rounding of a texel edge
    int differing = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) differing += a.rgb[i] != b.rgb[i];
    EXPECT_LE(differing, 3) << "offset (" << x.offset.x << ", " << x.offset.y << ") rotation " << x.rotation;
    EXPECT_GT(mean_of(a, 1), 0.01);
  }
  // the identity transform is no transform
  const PreparedScene identity = prepare(transformed_quad(UvTransform{}, false), kFacingQuad);
  EXPECT_FALSE(identity.tables.features.texture_transform);
}

// The alpha a MASK reads goes through the slot's transform as well: mapped onto the opaque texel of
// half_cut_quad's texture, no part of the quad is cut out.
TEST(TextureTransform, AppliesToTheAlphaOfMask) {
  Scene s = half_cut_quad(AlphaMode::mask);
  s.materials[0].base_color_transform = UvTransform{{0.5f, 0.f}, 0.f, {0.5f, 1.f}};
  const Split cut = split(render_prepared(prepare(s, kFacingQuad), sky_seen_directly(16, 4)).image);
  EXPECT_EQ(cut.zeros, 16 * 14);
}
