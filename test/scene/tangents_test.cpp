// Generated tangents (runtime/scene/tangents.h) against the frames a quad's coordinates imply, and
// the loader's NORMAL and TANGENT through node transforms.
#include <array>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "runtime/scene/scene.h"
#include "runtime/scene/tangents.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using nlohmann::json;

const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<std::array<std::uint32_t, 3>> kQuadTriangles = {{0, 1, 2}, {0, 2, 3}};

void expect_near(glm::vec4 got, glm::vec4 want) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], want[c], 1e-6f) << "component " << c;
}

TEST(Tangents, FollowIncreasingUAndTheImagesUpDirection) {
  const std::vector<glm::vec3> normals(4, glm::vec3(0, 0, 1));
  // glTF's v grows down the image: the top of the quad (y = 1) has v = 0
  const std::vector<glm::vec2> uv = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  for (const glm::vec4& t : generate_tangents(kQuad, normals, uv, kQuadTriangles)) expect_near(t, {1, 0, 0, 1});
  // u mirrored: the tangent turns round and w keeps the bitangent pointing up the image (+y)
  const std::vector<glm::vec2> mirrored = {{1, 1}, {0, 1}, {0, 0}, {1, 0}};
  for (const glm::vec4& t : generate_tangents(kQuad, normals, mirrored, kQuadTriangles)) expect_near(t, {-1, 0, 0, -1});
  // v running up the quad: the image is upside down, so up the image is -y
  const std::vector<glm::vec2> flipped = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const glm::vec4& t : generate_tangents(kQuad, normals, flipped, kQuadTriangles)) expect_near(t, {1, 0, 0, -1});
}

TEST(Tangents, AreOrthogonalToTheirNormalAndFlatWithoutNormals) {
  const std::vector<glm::vec2> uv = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  std::vector<glm::vec3> tilted(4, glm::normalize(glm::vec3(0.3f, 0.f, 1.f)));
  for (const glm::vec4& t : generate_tangents(kQuad, tilted, uv, kQuadTriangles)) {
    EXPECT_NEAR(glm::dot(glm::vec3(t), tilted[0]), 0.f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.f, 1e-6f);
    EXPECT_GT(t.x, 0.9f);
  }
  for (const glm::vec4& t : generate_tangents(kQuad, {}, uv, kQuadTriangles)) expect_near(t, {1, 0, 0, 1});
  // coordinates without area: any unit tangent orthogonal to the normal, never NaN
  const std::vector<glm::vec2> same(4, glm::vec2(0.5f));
  for (const glm::vec4& t : generate_tangents(kQuad, std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)), same, kQuadTriangles)) {
    EXPECT_NEAR(glm::length(glm::vec3(t)), 1.f, 1e-6f);
    EXPECT_NEAR(t.z, 0.f, 1e-6f);
  }
}

TEST(GltfNormals, NormalsAndTangentsAreReadAndTransformedAndMissingTangentsGenerated) {
  test::TempDir dir;
  test::write_file(dir / "n.ppm", std::string("P6\n1 1\n255\n") + std::string("\x80\x80\xff", 3));
  test::GltfWriter g;
  g.doc()["images"] = {{{"uri", "n.ppm"}}};
  g.doc()["textures"] = {{{"source", 0}}};
  const int mat = g.material({{"normalTexture", {{"index", 0}, {"scale", 0.5}}}, {"name", "bumpy"}});
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<glm::vec3> n(3, glm::vec3(0, 0, 1));
  const std::vector<glm::vec4> t(3, glm::vec4(1, 0, 0, 1));
  const std::vector<glm::vec2> uv = {{0, 1}, {1, 1}, {0, 0}};
  const int mesh = g.mesh(g.positions(p), -1, mat);
  auto& attributes = g.doc()["meshes"][mesh]["primitives"][0]["attributes"];
  attributes["NORMAL"] = g.accessor(g.view(n.data(), 36), 5126, 3, "VEC3");
  attributes["TEXCOORD_0"] = g.accessor(g.view(uv.data(), 24), 5126, 3, "VEC2");
  const int tangent_accessor = g.accessor(g.view(t.data(), 48), 5126, 3, "VEC4");
  // mirrored in x and turned 90 degrees about z
  g.roots({g.node({{"mesh", mesh}, {"scale", {-1.0, 1.0, 1.0}}, {"rotation", {0.0, 0.0, 0.7071068, 0.7071068}}})});
  const Scene generated = load_scene(g.write_gltf(dir.path(), "generated"));
  attributes["TANGENT"] = tangent_accessor;
  const Scene given = load_scene(g.write_gltf(dir.path(), "given"));
  const SceneMaterial& m = given.materials[0];
  ASSERT_GE(m.normal_texture, 0);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  EXPECT_FALSE(given.textures[static_cast<std::size_t>(m.normal_texture)].srgb);
  ASSERT_EQ(given.normals.size(), 3u);
  ASSERT_EQ(given.tangents.size(), 3u);
  // the node's matrix: x -> (0, -1, 0) (mirrored, then turned), y -> (-1, 0, 0), z -> z
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(given.normals[0][c], glm::vec3(0, 0, 1)[c], 1e-6f);
  expect_near(given.tangents[0], {0, -1, 0, -1});  // a mirror flips the bitangent's sign
  // generated from the transformed triangle, the tangent agrees with the file's
  ASSERT_EQ(generated.tangents.size(), 3u);
  for (const glm::vec4& tg : generated.tangents) expect_near(tg, given.tangents[0]);
  for (const std::string& w : given.warnings) EXPECT_EQ(w.find("normalTexture"), std::string::npos) << w;
}

}  // namespace
}  // namespace cohort
