// Every external model (scenes/external.json) loads with the triangle count the manifest gives.
#include <algorithm>

#include <gtest/gtest.h>

#include "runtime/scene/scene.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using test::shared_scenes;

struct SharedModel {
  const char* path;
  std::size_t triangles;
};

// The README counts fan-triangulate every polygon (n-gon = n - 2 triangles) and keep degenerate
// faces; the loaders do the same, so these are exact.
const SharedModel kModels[] = {
    {"bunny/bun_zipper.ply", 69451},
    {"armadillo/Armadillo.ply.gz", 345944},
    {"dragon-decimated-100k/dragon.ply", 100000},
    {"conference/conference.obj.gz", 331179},
    {"crytek-sponza/sponza.obj.gz", 279163},
    {"dabrovic-sponza/sponza.obj.gz", 66450},
    {"damaged-helmet-gltf/DamagedHelmet.gltf", 15452},
    {"cornell-box-mcguire/CornellBox-Original.obj", 36},
};

class SharedModels : public ::testing::TestWithParam<SharedModel> {};

TEST_P(SharedModels, TriangleCountMatchesReadme) {
  COHORT_REQUIRE_SHARED();
  const Scene s = load_scene(shared_scenes() / GetParam().path);
  EXPECT_EQ(s.triangle_count(), GetParam().triangles);
  EXPECT_EQ(s.material_ids.size(), s.triangle_count());
  EXPECT_TRUE(s.uvs.empty() || s.uvs.size() == s.positions.size());
  EXPECT_FALSE(s.bounds().empty());
}

INSTANTIATE_TEST_SUITE_P(Readme, SharedModels, ::testing::ValuesIn(kModels), [](const auto& info) {
  std::string name = info.param.path;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

TEST(SharedModelDetails, DamagedHelmetNodeRotationIsApplied) {
  COHORT_REQUIRE_SHARED();
  const Scene s = load_scene(shared_scenes() / "damaged-helmet-gltf/DamagedHelmet.gltf");
  // POSITION accessor min/max from the file, rotated by the node's quaternion (90 degrees about +X:
  // (x, y, z) -> (x, -z, y)).
  const glm::vec3 lo(-0.9474585652351379f, -1.18715500831604f, -0.9009949564933777f);
  const glm::vec3 hi(0.9424954056739807f, 0.8128451108932495f, 0.900973916053772f);
  const Bounds b = s.bounds();
  EXPECT_NEAR(b.lo.x, lo.x, 1e-5f);
  EXPECT_NEAR(b.hi.x, hi.x, 1e-5f);
  EXPECT_NEAR(b.lo.y, -hi.z, 1e-5f);
  EXPECT_NEAR(b.hi.y, -lo.z, 1e-5f);
  EXPECT_NEAR(b.lo.z, lo.y, 1e-5f);
  EXPECT_NEAR(b.hi.z, hi.y, 1e-5f);
}

TEST(SharedModelDetails, DamagedHelmetMaterialAndTextures) {
  COHORT_REQUIRE_SHARED();
  const Scene s = load_scene(shared_scenes() / "damaged-helmet-gltf/DamagedHelmet.gltf");
  ASSERT_EQ(s.materials.size(), 1u);
  const SceneMaterial& m = s.materials[0];
  EXPECT_EQ(m.name, "Material_MR");
  EXPECT_EQ(m.emission, glm::vec3(1.f));
  ASSERT_GE(m.base_color_texture, 0);
  ASSERT_GE(m.emission_texture, 0);
  ASSERT_GE(m.metallic_roughness_texture, 0);
  ASSERT_GE(m.normal_texture, 0);
  EXPECT_EQ(s.textures.size(), 4u);  // base colour, metallic-roughness, emission and normals; not occlusion
  EXPECT_FALSE(s.textures[static_cast<std::size_t>(m.metallic_roughness_texture)].srgb);
  const Texture& albedo = s.textures[static_cast<std::size_t>(m.base_color_texture)];
  EXPECT_EQ(albedo.width, 2048);
  EXPECT_EQ(albedo.height, 2048);
  EXPECT_EQ(albedo.rgba.size(), 2048u * 2048u * 4u);
  EXPECT_EQ(s.uvs.size(), s.positions.size());
  EXPECT_EQ(s.normals.size(), s.positions.size());
  EXPECT_EQ(s.tangents.size(), s.positions.size());  // generated: the file has none
  // what the loader leaves out by design is listed as not read: the occlusion map
  EXPECT_TRUE(s.notes.empty());
  ASSERT_EQ(s.unread_textures.size(), 1u);
  EXPECT_EQ(s.unread_textures[0].rfind("Default_AO.jpg: occlusion of 'Material_MR', not used", 0), 0u) << s.unread_textures[0];
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(SharedModelDetails, McGuireCornellBoxLightIsEmissiveAndFacesDown) {
  COHORT_REQUIRE_SHARED();
  const Scene s = load_scene(shared_scenes() / "cornell-box-mcguire/CornellBox-Original.obj");
  ASSERT_EQ(s.emissive_triangle_count(), 2u);
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    const SceneMaterial& m = s.materials[s.material_ids[t]];
    if (!m.is_emissive()) continue;
    EXPECT_EQ(m.emission, glm::vec3(17.f, 12.f, 4.f));
    EXPECT_LT(test::triangle_normal(s, t).y, -0.99f);
  }
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(SharedModelDetails, DabrovicSponzaFindsTexturesDespiteLetterCase) {
  COHORT_REQUIRE_SHARED();
  const Scene s = load_scene(shared_scenes() / "dabrovic-sponza/sponza.obj.gz");
  EXPECT_GE(s.textures.size(), 10u);
  EXPECT_EQ(s.uvs.size(), s.positions.size());
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("not found"), std::string::npos) << w;
}

TEST(SharedModelDetails, ModelsWithoutLightsWarn) {
  COHORT_REQUIRE_SHARED();
  const Scene s = load_scene(shared_scenes() / "bunny/bun_zipper_res4.ply");
  EXPECT_EQ(s.triangle_count(), 948u);
  EXPECT_EQ(s.emissive_triangle_count(), 0u);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.back().find("no light"), std::string::npos);
}

}  // namespace
}  // namespace cohort
