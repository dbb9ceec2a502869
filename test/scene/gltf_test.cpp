// glTF loading on files written by the test: transforms, index widths, layouts, materials, cameras.
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "runtime/scene/scene.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using nlohmann::json;
using test::GltfWriter;
using test::TempDir;

const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<std::uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

// One mesh node with the quad, indexed with `indices` (or not, when it is empty).
template <typename T>
Scene load_quad(const TempDir& dir, const std::vector<T>& indices, const std::string& stem) {
  GltfWriter g;
  const int pos = g.positions(kQuad);
  const int idx = indices.empty() ? -1 : g.indices(indices);
  g.roots({g.node({{"mesh", g.mesh(pos, idx)}})});
  return load_scene(g.write_gltf(dir.path(), stem));
}

void expect_same_triangles(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) EXPECT_EQ(a.positions[i], b.positions[i]) << i;
}

TEST(Gltf, NestedNodeTransformsComposeAsMatrixProduct) {
  TempDir dir;
  GltfWriter g;
  const glm::vec3 v(0.3f, -0.7f, 1.1f);
  const int mesh = g.mesh(g.positions({v, v + glm::vec3(1, 0, 0), v + glm::vec3(0, 1, 0)}));
  const glm::quat parent_r = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3)));
  const glm::quat child_r = glm::angleAxis(-1.3f, glm::normalize(glm::vec3(-2, 0.5f, 1)));
  const int child = g.node({{"mesh", mesh},
                            {"translation", {4.0, -1.0, 0.5}},
                            {"rotation", {child_r.x, child_r.y, child_r.z, child_r.w}},
                            {"scale", {0.5, 2.0, 3.0}}});
  const int parent = g.node({{"children", {child}},
                             {"translation", {1.0, 2.0, 3.0}},
                             {"rotation", {parent_r.x, parent_r.y, parent_r.z, parent_r.w}},
                             {"scale", {2.0, 2.0, 2.0}}});
  g.roots({parent});
  const Scene s = load_scene(g.write_gltf(dir.path(), "nested"));
  auto trs = [](glm::vec3 t, glm::quat r, glm::vec3 sc) {
    return glm::translate(glm::mat4(1.f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.f), sc);
  };
  const glm::mat4 world = trs({1, 2, 3}, parent_r, glm::vec3(2)) * trs({4, -1, 0.5f}, child_r, {0.5f, 2, 3});
  const glm::vec3 expected(world * glm::vec4(v, 1.f));
  ASSERT_EQ(s.triangle_count(), 1u);
  EXPECT_NEAR(s.positions[0].x, expected.x, 1e-4f);
  EXPECT_NEAR(s.positions[0].y, expected.y, 1e-4f);
  EXPECT_NEAR(s.positions[0].z, expected.z, 1e-4f);
}

TEST(Gltf, NodeMatrixIsColumnMajor) {
  TempDir dir;
  GltfWriter g;
  const int mesh = g.mesh(g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
  // Translation (5, 6, 7) sits in elements 12..14 of a column-major matrix.
  g.roots({g.node({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1}}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "matrix"));
  EXPECT_EQ(s.positions[0], glm::vec3(5, 6, 7));
  EXPECT_EQ(s.positions[1], glm::vec3(6, 6, 7));
}

TEST(Gltf, IndexWidthsAndNonIndexedGiveTheSameTriangles) {
  TempDir dir;
  const Scene u8 = load_quad(dir, std::vector<std::uint8_t>(kQuadIndices.begin(), kQuadIndices.end()), "u8");
  const Scene u16 =
      load_quad(dir, std::vector<std::uint16_t>(kQuadIndices.begin(), kQuadIndices.end()), "u16");
  const Scene u32 = load_quad(dir, kQuadIndices, "u32");
  std::vector<glm::vec3> soup;
  for (std::uint32_t i : kQuadIndices) soup.push_back(kQuad[i]);
  GltfWriter g;
  g.roots({g.node({{"mesh", g.mesh(g.positions(soup))}})});
  const Scene plain = load_scene(g.write_gltf(dir.path(), "plain"));
  ASSERT_EQ(u8.triangle_count(), 2u);
  expect_same_triangles(u8, u16);
  expect_same_triangles(u8, u32);
  expect_same_triangles(u8, plain);
}

TEST(Gltf, InterleavedStrideAndByteOffsetAreRespected) {
  TempDir dir;
  GltfWriter g;
  // Each vertex: 4 bytes of padding, the position, 8 more bytes: stride 24, offset 4.
  std::vector<float> interleaved;
  for (const glm::vec3& p : kQuad) interleaved.insert(interleaved.end(), {-9.f, p.x, p.y, p.z, -9.f, -9.f});
  const int view = g.view(interleaved.data(), interleaved.size() * sizeof(float), 24);
  const int pos = g.accessor(view, 5126, kQuad.size(), "VEC3", 4);
  g.roots({g.node({{"mesh", g.mesh(pos, g.indices(kQuadIndices))}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "stride"));
  expect_same_triangles(s, load_quad(dir, kQuadIndices, "reference"));
}

TEST(Gltf, BinaryGlbLoads) {
  TempDir dir;
  GltfWriter g;
  g.roots({g.node({{"mesh", g.mesh(g.positions(kQuad), g.indices(kQuadIndices))}})});
  const Scene s = load_scene(g.write_glb(dir.path(), "quad"));
  expect_same_triangles(s, load_quad(dir, kQuadIndices, "reference"));
}

TEST(Gltf, BinaryContentUnderAGltfNameLoads) {
  TempDir dir;
  GltfWriter g;
  g.roots({g.node({{"mesh", g.mesh(g.positions(kQuad), g.indices(kQuadIndices))}})});
  test::write_file(dir / "misnamed.gltf", g.glb_bytes());
  EXPECT_EQ(load_scene(dir / "misnamed.gltf").triangle_count(), 2u);
}

TEST(Gltf, MeshesAreInstancedPerNodePath) {
  TempDir dir;
  GltfWriter g;
  const int leaf = g.node({{"mesh", g.mesh(g.positions(kQuad), g.indices(kQuadIndices))}});
  const int a = g.node({{"children", {leaf}}, {"translation", {10.0, 0.0, 0.0}}});
  const int b = g.node({{"children", {leaf}}, {"translation", {20.0, 0.0, 0.0}}});
  g.roots({a, b});
  const Scene s = load_scene(g.write_gltf(dir.path(), "instances"));
  ASSERT_EQ(s.triangle_count(), 4u);
  EXPECT_EQ(s.positions[0].x, 10.f);
  EXPECT_EQ(s.positions[6].x, 20.f);
}

TEST(Gltf, SharedSubtreesExpandToEveryPath) {
  TempDir dir;
  GltfWriter g;
  // Six levels of a node whose two children are both the level below: 64 paths to the mesh, each an
  // instance (the loader counts instances on the graph before walking it, and must count them right).
  int below = g.node({{"mesh", g.mesh(g.positions(kQuad), g.indices(kQuadIndices))}});
  for (int level = 0; level < 6; ++level) below = g.node({{"children", {below, below}}});
  g.roots({below, below});
  EXPECT_EQ(load_scene(g.write_gltf(dir.path(), "dag")).triangle_count(), 2u * 128u);
}

TEST(Gltf, NegativeScaleKeepsTheFrontFace) {
  TempDir dir;
  GltfWriter g;
  const int mesh = g.mesh(g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));  // front faces +Z
  g.roots({g.node({{"mesh", mesh}, {"scale", {-1.0, 1.0, 1.0}}}),
           g.node({{"mesh", mesh}, {"scale", {1.0, 1.0, -1.0}}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "mirror"));
  ASSERT_EQ(s.triangle_count(), 2u);
  EXPECT_NEAR(test::triangle_normal(s, 0).z, 1.f, 1e-6f);   // mirrored in x: still faces +Z
  EXPECT_NEAR(test::triangle_normal(s, 1).z, -1.f, 1e-6f);  // mirrored in z: faces -Z
  EXPECT_EQ(s.positions[1], glm::vec3(0, 1, 0));            // corners 1 and 2 swapped
}

TEST(Gltf, StripsAndFansAreTriangulatedAndPointsSkipped) {
  TempDir dir;
  GltfWriter g;
  const int pos = g.positions(kQuad);
  const int strip = g.mesh(pos, g.indices(std::vector<std::uint16_t>{0, 1, 3, 2}), -1, 5);
  const int fan = g.mesh(pos, -1, -1, 6);
  const int points = g.mesh(pos, -1, -1, 0);
  g.roots({g.node({{"mesh", strip}}), g.node({{"mesh", fan}}), g.node({{"mesh", points}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "topologies"));
  ASSERT_EQ(s.triangle_count(), 4u);
  for (std::size_t t = 0; t < 4; ++t) EXPECT_NEAR(test::triangle_normal(s, t).z, 1.f, 1e-6f) << t;
  bool warned = false;
  for (const auto& w : s.warnings) warned |= w.find("point or line") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Gltf, MaterialsAndExtensions) {
  TempDir dir;
  GltfWriter g;
  const int m = g.material(
      {{"name", "glass"},
       {"doubleSided", true},
       {"emissiveFactor", {0.5, 0.25, 1.0}},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.1, 0.2, 0.3, 0.4}}, {"metallicFactor", 0.6}, {"roughnessFactor", 0.7}}},
       {"extensions",
        {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}},
         {"KHR_materials_transmission", {{"transmissionFactor", 0.9}}},
         {"KHR_materials_ior", {{"ior", 1.33}}}}}});
  const int pos = g.positions(kQuad);
  g.roots({g.node({{"mesh", g.mesh(pos, g.indices(kQuadIndices), m)}}),
           g.node({{"mesh", g.mesh(pos, g.indices(kQuadIndices))}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "materials"));
  ASSERT_EQ(s.materials.size(), 2u);
  const SceneMaterial& glass = s.materials[0];
  EXPECT_EQ(glass.name, "glass");
  EXPECT_TRUE(glass.double_sided);
  EXPECT_NEAR(glass.emission.x, 2.f, 1e-6f);
  EXPECT_NEAR(glass.emission.y, 1.f, 1e-6f);
  EXPECT_NEAR(glass.emission.z, 4.f, 1e-6f);
  EXPECT_NEAR(glass.base_color.z, 0.3f, 1e-6f);
  EXPECT_NEAR(glass.alpha, 0.4f, 1e-6f);
  EXPECT_NEAR(glass.metallic, 0.6f, 1e-6f);
  EXPECT_NEAR(glass.roughness, 0.7f, 1e-6f);
  EXPECT_NEAR(glass.transmission, 0.9f, 1e-6f);
  EXPECT_NEAR(glass.ior, 1.33f, 1e-6f);
  EXPECT_EQ(s.materials[1].name, "default");  // for the primitive without a material
  EXPECT_EQ(s.material_ids, (std::vector<std::uint32_t>{0, 0, 1, 1}));
  EXPECT_EQ(s.emissive_triangle_count(), 2u);
}

TEST(Gltf, BaseColourTextureAndTexcoordsAreLoaded) {
  TempDir dir;
  // A 2x1 binary PPM: red, then green. stb_image (through tinygltf) decodes it like any image.
  test::write_file(dir / "tex.ppm",
                   std::string("P6\n2 1\n255\n") + std::string("\xff\x00\x00\x00\xff\x00", 6));
  GltfWriter g;
  g.doc()["images"] = {{{"uri", "tex.ppm"}}};
  g.doc()["textures"] = {{{"source", 0}}};
  const int m = g.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const int uv_acc = g.accessor(g.view(uv.data(), uv.size() * sizeof(glm::vec2)), 5126, uv.size(), "VEC2");
  const int with_uv = g.mesh(g.positions(kQuad), g.indices(kQuadIndices), m);
  g.doc()["meshes"][with_uv]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv_acc;
  const int without_uv = g.mesh(g.positions(kQuad), g.indices(kQuadIndices));
  g.roots({g.node({{"mesh", without_uv}}), g.node({{"mesh", with_uv}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "textured"));
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 2);
  EXPECT_EQ(s.textures[0].height, 1);
  EXPECT_EQ(s.textures[0].rgba, (std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 255}));
  EXPECT_EQ(s.materials[0].base_color_texture, 0);
  ASSERT_EQ(s.uvs.size(), 12u);  // the primitive without TEXCOORD_0 gets zeros
  EXPECT_EQ(s.uvs[0], glm::vec2(0));
  EXPECT_EQ(s.uvs[6 + 2], glm::vec2(1, 1));
}

TEST(Gltf, NoTexcoordsLeavesUvsEmpty) {
  TempDir dir;
  EXPECT_TRUE(load_quad(dir, kQuadIndices, "nouv").uvs.empty());
}

TEST(Gltf, FirstPerspectiveCameraInNodeOrder) {
  TempDir dir;
  GltfWriter g;
  g.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                        {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
  const glm::quat r = glm::angleAxis(glm::radians(90.f), glm::vec3(0, 1, 0));  // -Z turns to -X
  const int cam = g.node({{"camera", 0}, {"translation", {0.0, 0.0, 2.0}}});
  const int parent =
      g.node({{"children", {cam}}, {"translation", {1.0, 0.0, 0.0}}, {"rotation", {r.x, r.y, r.z, r.w}}});
  const int other = g.node({{"camera", 1}});
  g.roots({parent, other, g.node({{"mesh", g.mesh(g.positions(kQuad), g.indices(kQuadIndices))}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "camera"));
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_NEAR(s.camera->vfov_degrees, glm::degrees(0.5f), 1e-4f);
  EXPECT_NEAR(s.camera->eye.x, 3.f, 1e-5f);  // (0,0,2) rotated to (2,0,0), then moved by (1,0,0)
  EXPECT_NEAR(s.camera->eye.z, 0.f, 1e-5f);
  const glm::vec3 forward = glm::normalize(s.camera->target - s.camera->eye);
  EXPECT_NEAR(forward.x, -1.f, 1e-5f);
  EXPECT_NEAR(s.camera->up.y, 1.f, 1e-5f);
}

TEST(Gltf, PunctualLightsArePlacedByTheirNodes) {
  TempDir dir;
  GltfWriter g;
  g.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
  g.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 8.0}},
      {{"type", "spot"}, {"intensity", 3.0}, {"range", 10.0},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}}};
  const glm::quat down = glm::angleAxis(glm::radians(-90.f), glm::vec3(1, 0, 0));  // -Z turns to -Y
  const int point = g.node({{"translation", {1.0, 2.0, 3.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const int spot = g.node({{"translation", {0.0, 5.0, 0.0}},
                           {"rotation", {down.x, down.y, down.z, down.w}},
                           {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  const int sun = g.node({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  g.roots({point, spot, sun, g.node({{"mesh", g.mesh(g.positions(kQuad), g.indices(kQuadIndices))}})});
  const Scene s = load_scene(g.write_gltf(dir.path(), "lights"));
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, SceneLight::Type::point);
  EXPECT_EQ(s.lights[0].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(s.lights[0].intensity, glm::vec3(8, 4, 2));
  EXPECT_EQ(s.lights[1].type, SceneLight::Type::spot);
  EXPECT_NEAR(s.lights[1].direction.y, -1.f, 1e-6f);
  EXPECT_NEAR(s.lights[1].position.y, 5.f, 1e-6f);
  EXPECT_FLOAT_EQ(s.lights[1].inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(s.lights[1].outer_cone, 0.5f);
  // the directional light and the range are reported, not silently dropped
  int warnings = 0;
  for (const auto& w : s.warnings) warnings += w.find("directional") != std::string::npos || w.find("range") != std::string::npos;
  EXPECT_EQ(warnings, 2);
}

TEST(Gltf, BadPunctualLightsAreInputErrors) {
  TempDir dir;
  for (const auto& [stem, light, index] :
       {std::tuple<std::string, json, int>{"missing", {{"type", "point"}}, 3},
        {"cone", {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}}}, 0},
        {"negative", {{"type", "point"}, {"intensity", -1.0}}, 0}}) {
    GltfWriter g;
    g.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {light};
    g.roots({g.node({{"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}}),
             g.node({{"mesh", g.mesh(g.positions(kQuad), g.indices(kQuadIndices))}})});
    test::expect_input_error(g.write_gltf(dir.path(), stem), "light");
  }
}

}  // namespace
}  // namespace cohort
