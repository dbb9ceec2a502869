// The glTF metallic-roughness mapping (bsdf_from_gltf / bsdf_from_material).
#include <gtest/gtest.h>

#include "common/shading/bsdf.h"
#include "common/shading/sheen.h"

namespace {

const co_vec3 kBase = v3(0.8f, 0.4f, 0.2f);

Material material(float metallic, float roughness, float transmission, float ior) {
  Material m{};
  m.base_color = {kBase.x, kBase.y, kBase.z, 1.0f};
  m.metallic = metallic;
  m.roughness = roughness;
  m.transmission = transmission;
  m.ior = ior;
  m.base_color_texture = -1;
  return m;
}

}  // namespace

TEST(GltfMapping, CornellBoxMaterialsAreLambertian) {
  // metallic 0, roughness 1: Mitsuba's diffuse, whatever the random number
  const Material m = material(0.0f, 1.0f, 0.0f, 1.5f);
  for (float u : {0.0f, 0.5f, 0.999999f}) {
    const Bsdf b = bsdf_from_material(&m, kBase, u);
    EXPECT_EQ(b.type, BSDF_DIFFUSE);
    EXPECT_EQ(b.color.x, kBase.x);
  }
}

TEST(GltfMapping, MetalIsConductorWithBaseColourF0) {
  const Material m = material(1.0f, 0.5f, 0.0f, 1.5f);
  for (float u : {0.0f, 0.5f, 0.999999f}) {
    const Bsdf b = bsdf_from_material(&m, kBase, u);
    EXPECT_EQ(b.type, BSDF_CONDUCTOR);
    EXPECT_FLOAT_EQ(b.alpha, 0.25f);  // alpha = roughness^2
    EXPECT_EQ(b.color.y, kBase.y);
  }
  const Material mirror = material(1.0f, 0.0f, 0.0f, 1.5f);
  const Bsdf smooth = bsdf_from_material(&mirror, kBase, 0.3f);
  EXPECT_TRUE(bsdf_is_delta(&smooth));
}

TEST(GltfMapping, DielectricsAndTransmission) {
  const Material rough = material(0.0f, 0.5f, 0.0f, 1.45f);
  Bsdf b = bsdf_from_material(&rough, kBase, 0.3f);
  EXPECT_EQ(b.type, BSDF_PLASTIC);
  EXPECT_FLOAT_EQ(b.eta, 1.45f);
  EXPECT_FLOAT_EQ(b.alpha, 0.25f);
  const Material glass = material(0.0f, 0.0f, 1.0f, 1.5f);
  b = bsdf_from_material(&glass, kBase, 0.3f);
  EXPECT_EQ(b.type, BSDF_DIELECTRIC);
  EXPECT_TRUE(bsdf_is_delta(&b));
  const Material bad_ior = material(0.0f, 0.2f, 1.0f, 0.0f);
  b = bsdf_from_material(&bad_ior, kBase, 0.3f);
  EXPECT_FLOAT_EQ(b.eta, 1.5f);  // glTF default
}

// metallic in (0, 1): a conductor with probability `metallic`, decided by u_select alone.
TEST(GltfMapping, PartialMetalIsAStochasticMix) {
  const Material m = material(0.3f, 0.6f, 0.5f, 1.5f);
  int conductor = 0, dielectric = 0, plastic = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const float u = (i + 0.5f) / n;
    const Bsdf b = bsdf_from_material(&m, kBase, u);
    const Bsdf again = bsdf_from_material(&m, kBase, u);
    ASSERT_EQ(b.type, again.type);
    if (b.type == BSDF_CONDUCTOR) ++conductor;
    if (b.type == BSDF_DIELECTRIC) ++dielectric;
    if (b.type == BSDF_PLASTIC) ++plastic;
  }
  EXPECT_NEAR(conductor / double(n), 0.3, 1e-3);
  EXPECT_NEAR(dielectric / double(n), 0.7 * 0.5, 1e-3);
  EXPECT_NEAR(plastic / double(n), 0.7 * 0.5, 1e-3);
}
