// What a glTF file asks for beyond the loader is named once per feature, with its material count.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "runtime/scene/scene.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using nlohmann::json;
using test::GltfWriter;
using test::TempDir;

// A triangle per material, each of the given materials; images are 1x1 PPMs.
GltfWriter triangles_with(const TempDir& dir, const std::vector<json>& materials) {
  test::write_file(dir / "px.ppm", std::string("P6\n1 1\n255\n") + std::string("\x80\x80\xff", 3));
  GltfWriter g;
  g.doc()["images"] = {{{"uri", "px.ppm"}}};
  g.doc()["textures"] = {{{"source", 0}}};
  std::vector<int> roots;
  const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {0, 1}};
  for (const json& m : materials) {
    const int pos = g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int mesh = g.mesh(pos, -1, g.material(m));
    g.doc()["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        g.accessor(g.view(uv.data(), uv.size() * sizeof(glm::vec2)), 5126, uv.size(), "VEC2");
    roots.push_back(g.node({{"mesh", mesh}}));
  }
  g.roots(roots);
  return g;
}

std::size_t lines_containing(const std::vector<std::string>& lines, const std::string& what) {
  return static_cast<std::size_t>(
      std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(what) != std::string::npos; }));
}

TEST(GltfUnhonoured, EachFeatureIsOneWarningWithItsMaterialCount) {
  TempDir dir;
  const json tex = {{"index", 0}};
  const json transformed = {
      {"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 2}}}}}}}};
  GltfWriter g = triangles_with(dir, {{{"pbrMetallicRoughness", transformed},
                                       {"alphaMode", "BLEND"},
                                       {"extensions", {{"KHR_materials_iridescence", json::object()}}}},
                                      {{"pbrMetallicRoughness", transformed},
                                       {"extensions", {{"KHR_materials_iridescence", json::object()}}}},
                                      {{"alphaMode", "OPAQUE"}, {"occlusionTexture", tex}}});
  g.doc()["extensionsUsed"] = {"KHR_materials_iridescence", "EXT_meshopt_compression", "KHR_texture_transform"};
  const Scene s = load_scene(g.write_gltf(dir.path(), "features"));
  EXPECT_EQ(lines_containing(s.warnings, "KHR_texture_transform"), 0u);  // honoured
  // its texCoord replaces the reference's: set 2 is not read
  EXPECT_EQ(lines_containing(s.warnings, "TEXCOORD_2 or above (TEXCOORD_0 used): 2 materials"), 1u);
  EXPECT_EQ(lines_containing(s.warnings, "alphaMode"), 0u);  // honoured (kernels/common/accel/alpha.h)
  EXPECT_EQ(lines_containing(s.warnings, "extension KHR_materials_iridescence: 2 materials"), 1u);
  // an extension no material carries is still named, once, and the iridescence is not named twice
  EXPECT_EQ(lines_containing(s.warnings, "ignored (optional, not implemented): EXT_meshopt_compression"), 1u);
  EXPECT_EQ(lines_containing(s.warnings, "KHR_materials_iridescence"), 1u);
  // occlusion is left out by design: listed as a texture not read, neither a warning nor a note
  EXPECT_EQ(lines_containing(s.warnings, "occlusion"), 0u);
  EXPECT_TRUE(s.notes.empty());
  ASSERT_EQ(s.unread_textures.size(), 1u);
  EXPECT_NE(s.unread_textures[0].find(": occlusion of 'material 2', not used"), std::string::npos)
      << s.unread_textures[0];
}

TEST(GltfUnhonoured, ASceneOfHonouredFeaturesWarnsNothing) {
  TempDir dir;
  GltfWriter g = triangles_with(
      dir, {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.5}}},
             {"emissiveTexture", {{"index", 0}}},
             {"emissiveFactor", {1, 1, 1}},
             {"extensions", {{"KHR_materials_ior", {{"ior", 1.4}}}}}},
            {{"alphaMode", "MASK"}, {"alphaCutoff", 0.3}},
            {{"pbrMetallicRoughness",
              {{"baseColorTexture",
                {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2, 2}}, {"rotation", 0.5}}}}}}}}}},
            {{"alphaMode", "BLEND"}}});
  g.doc()["extensionsUsed"] = {"KHR_materials_ior"};
  const Scene s = load_scene(g.write_gltf(dir.path(), "plain"));
  EXPECT_EQ(lines_containing(s.warnings, ""), lines_containing(s.warnings, "no light")) << s.warnings.front();
  EXPECT_TRUE(s.notes.empty());
}

TEST(GltfUnhonoured, RequiredExtensionsBeyondTheLoaderAreStillRefused) {
  TempDir dir;
  GltfWriter g = triangles_with(dir, {{{"extensions", {{"KHR_materials_iridescence", json::object()}}}}});
  g.doc()["extensionsUsed"] = g.doc()["extensionsRequired"] = {"KHR_materials_iridescence"};
  test::expect_input_error(g.write_gltf(dir.path(), "required"), "KHR_materials_iridescence");
}

TEST(GltfUnhonoured, ClearcoatIsHonouredAndMayBeRequired) {
  TempDir dir;
  GltfWriter g = triangles_with(dir, {{{"extensions", {{"KHR_materials_clearcoat",
                                                        {{"clearcoatFactor", 1}, {"clearcoatTexture", {{"index", 0}}},
                                                         {"clearcoatNormalTexture", {{"index", 0}, {"texCoord", 2}}}}}}}}});
  g.doc()["extensionsUsed"] = g.doc()["extensionsRequired"] = {"KHR_materials_clearcoat"};
  const Scene s = load_scene(g.write_gltf(dir.path(), "coat"));
  EXPECT_EQ(lines_containing(s.warnings, "KHR_materials_clearcoat"), 0u);
  // the coat's textures count among the material's: its normal map's set 2 is named
  EXPECT_EQ(lines_containing(s.warnings, "TEXCOORD_2 or above (TEXCOORD_0 used): 1 material"), 1u);
  EXPECT_EQ(s.materials.at(0).clearcoat.factor, 1.f);
}

TEST(GltfUnhonoured, HigherCoordinateSetsAreCountedByMaterial) {
  TempDir dir;
  const json set2 = {{"index", 0}, {"texCoord", 2}};
  GltfWriter g = triangles_with(dir, {{{"emissiveTexture", set2}, {"emissiveFactor", {1, 1, 1}}},
                                      {{"pbrMetallicRoughness", {{"baseColorTexture", set2}}}},
                                      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}}});
  const Scene s = load_scene(g.write_gltf(dir.path(), "sets"));
  EXPECT_EQ(lines_containing(s.warnings, "TEXCOORD_2 or above (TEXCOORD_0 used): 2 materials"), 1u);
  // TEXCOORD_1 is read, but these triangles have none
  EXPECT_EQ(lines_containing(s.warnings, "TEXCOORD_1, which no primitive has, are ignored: 1 material"), 1u);
}

}  // namespace
}  // namespace cohort
