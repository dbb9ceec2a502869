// The scenes in scenes/ (written by scripts/make-scenes.py) load as the tests and docs/decisions.md expect.
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "runtime/scene/scene.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using test::source_dir;
using test::triangle_normal;

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

glm::vec3 centroid(const Scene& s, std::size_t t) {
  return (s.positions[3 * t] + s.positions[3 * t + 1] + s.positions[3 * t + 2]) / 3.f;
}

const SceneMaterial& material_named(const Scene& s, const std::string& name) {
  for (const auto& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

TEST(ShippedScenes, CornellBoxCountsAndCamera) {
  const Scene s = load_scene(source_dir() / "scenes/cornell-box.gltf");
  EXPECT_EQ(s.triangle_count(), 38u);  // Mitsuba's cbox meshes: 8 OBJs, quads fanned
  EXPECT_EQ(s.materials.size(), 5u);
  EXPECT_EQ(s.emissive_triangle_count(), 2u);
  ASSERT_TRUE(s.camera.has_value());
  expect_near(s.camera->eye, {278.f, 273.f, -800.f}, 1e-3f);
  expect_near(glm::normalize(s.camera->target - s.camera->eye), {0.f, 0.f, 1.f}, 1e-6f);
  expect_near(s.camera->up, {0.f, 1.f, 0.f}, 1e-6f);
  EXPECT_NEAR(s.camera->vfov_degrees, 39.3077f, 1e-4f);
  const Bounds b = s.bounds();
  expect_near(b.lo, {0.f, 0.f, 0.f}, 1e-3f);
  expect_near(b.hi, {556.f, 548.8f, 559.2f}, 1e-3f);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(ShippedScenes, CornellBoxAlbedosAreMitsubaRgb) {
  const Scene s = load_scene(source_dir() / "scenes/cornell-box.gltf");
  expect_near(material_named(s, "white").base_color, {0.885809f, 0.698859f, 0.666422f}, 1e-6f);
  expect_near(material_named(s, "red").base_color, {0.570068f, 0.0430135f, 0.0443706f}, 1e-6f);
  expect_near(material_named(s, "green").base_color, {0.105421f, 0.37798f, 0.076425f}, 1e-6f);
  expect_near(material_named(s, "box").base_color, {0.45f, 0.30f, 0.90f}, 1e-6f);
  expect_near(material_named(s, "light").base_color, {0.936461f, 0.740433f, 0.705267f}, 1e-6f);
}

TEST(ShippedScenes, CornellBoxLuminaireFacesDownWithMitsubaRadiance) {
  const Scene s = load_scene(source_dir() / "scenes/cornell-box.gltf");
  std::size_t lights = 0;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    const SceneMaterial& m = s.materials[s.material_ids[t]];
    if (!m.is_emissive()) continue;
    ++lights;
    expect_near(m.emission, {18.387f, 10.9873f, 2.75357f}, 1e-4f);
    EXPECT_FALSE(m.double_sided);  // one-sided emitter, like Mitsuba's area light
    expect_near(triangle_normal(s, t), {0.f, -1.f, 0.f}, 1e-6f);
    EXPECT_NEAR(centroid(s, t).y, 548.3f, 1e-3f);  // moved 0.5 down, as shapes.xml does
  }
  EXPECT_EQ(lights, 2u);
}

TEST(ShippedScenes, CornellBoxWallsFaceIntoTheRoomAndBlocksFaceOut) {
  const Scene s = load_scene(source_dir() / "scenes/cornell-box.gltf");
  const glm::vec3 room(278.f, 274.4f, 279.6f);
  const glm::vec3 small_block(186.f, 82.5f, 168.5f), large_block(368.5f, 165.f, 351.5f);
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    const SceneMaterial& m = s.materials[s.material_ids[t]];
    const glm::vec3 c = centroid(s, t), n = triangle_normal(s, t);
    if (m.name == "box") {
      const glm::vec3 block =
          glm::distance(c, small_block) < glm::distance(c, large_block) ? small_block : large_block;
      EXPECT_GT(glm::dot(n, c - block), 0.f) << "block triangle " << t;
    } else if (!m.is_emissive()) {
      EXPECT_GT(glm::dot(n, room - c), 0.f) << m.name << " triangle " << t;
    }
  }
}

TEST(ShippedScenes, FurnaceSphereIsClosedAndFacesInward) {
  const Scene s = load_scene(source_dir() / "scenes/furnace-sphere.gltf");
  EXPECT_EQ(s.triangle_count(), 2u * 64u * 31u);  // 64 segments x 32 rings, caps are single triangles
  ASSERT_EQ(s.materials.size(), 1u);
  const SceneMaterial& m = s.materials[0];
  expect_near(m.base_color, glm::vec3(0.5f), 0.f);
  expect_near(m.emission, glm::vec3(1.f), 0.f);
  EXPECT_FALSE(m.double_sided);
  EXPECT_EQ(s.emissive_triangle_count(), s.triangle_count());
  // Closed: every directed edge has its reverse in another triangle.
  std::map<std::tuple<float, float, float, float, float, float>, int> edges;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    EXPECT_LT(glm::dot(triangle_normal(s, t), centroid(s, t)), 0.f) << "triangle " << t << " faces out";
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = s.positions[3 * t + k], b = s.positions[3 * t + (k + 1) % 3];
      EXPECT_NEAR(glm::length(a), 1.f, 1e-5f);
      ++edges[{a.x, a.y, a.z, b.x, b.y, b.z}];
    }
  }
  for (const auto& [e, count] : edges) {
    const auto [ax, ay, az, bx, by, bz] = e;
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({bx, by, bz, ax, ay, az}), 1u);
  }
  ASSERT_TRUE(s.camera.has_value());
  expect_near(s.camera->eye, glm::vec3(0.f), 0.f);
  expect_near(glm::normalize(s.camera->target - s.camera->eye), {0.f, 0.f, -1.f}, 1e-6f);
  EXPECT_NEAR(s.camera->vfov_degrees, 60.f, 1e-4f);
}

TEST(ShippedScenes, SingleTriangleFacesItsCamera) {
  const Scene s = load_scene(source_dir() / "scenes/single-triangle.gltf");
  ASSERT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(s.emissive_triangle_count(), 1u);
  ASSERT_TRUE(s.camera.has_value());
  expect_near(s.camera->eye, {0.f, 0.f, 4.f}, 1e-6f);
  expect_near(glm::normalize(s.camera->target - s.camera->eye), {0.f, 0.f, -1.f}, 1e-6f);
  expect_near(triangle_normal(s, 0), {0.f, 0.f, 1.f}, 1e-6f);
  EXPECT_NEAR(s.camera->vfov_degrees, 45.f, 1e-4f);
}

TEST(ShippedScenes, QuadLightObjHasADownwardEmitter) {
  const Scene s = load_scene(source_dir() / "scenes/quad-light.obj");
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.emissive_triangle_count(), 2u);
  EXPECT_FALSE(s.camera.has_value());
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    const SceneMaterial& m = s.materials[s.material_ids[t]];
    if (m.is_emissive()) {
      expect_near(m.emission, glm::vec3(10.f), 0.f);
      expect_near(triangle_normal(s, t), {0.f, -1.f, 0.f}, 1e-6f);
    } else {
      expect_near(m.base_color, glm::vec3(0.8f), 1e-6f);
      expect_near(triangle_normal(s, t), {0.f, 1.f, 0.f}, 1e-6f);
    }
  }
}

}  // namespace
}  // namespace cohort
