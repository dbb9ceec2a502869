// Scene's own methods and the protocol's framing camera.
#include <gtest/gtest.h>

#include "runtime/scene/scene.h"

namespace cohort {
namespace {

Scene two_triangles() {
  Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-2, 3, 1}, {0, 0, -4}, {1, 1, 1}};
  s.material_ids = {0, 1};
  s.materials = {SceneMaterial{.name = "dull"}, SceneMaterial{.name = "lamp", .emission = {0, 0, 1}}};
  return s;
}

TEST(Scene, BoundsCoverEveryVertex) {
  const Bounds b = two_triangles().bounds();
  EXPECT_EQ(b.lo, glm::vec3(-2, 0, -4));
  EXPECT_EQ(b.hi, glm::vec3(1, 3, 1));
  EXPECT_TRUE(Scene{}.bounds().empty());
}

TEST(Scene, EmissiveTriangleCount) { EXPECT_EQ(two_triangles().emissive_triangle_count(), 1u); }

TEST(Scene, GeometryBytes) {
  Scene s = two_triangles();
  EXPECT_EQ(s.geometry_bytes(), 2 * (48 + 4) + 2 * 80u);
  s.uvs.assign(6, glm::vec2(0));
  s.textures.push_back(Texture{.width = 2, .height = 2, .rgba = std::vector<std::uint8_t>(16)});
  EXPECT_EQ(s.geometry_bytes(), 2 * (48 + 4) + 2 * 80u + 6 * 8u + 16u);
}

TEST(Scene, FramingCameraFollowsTheBenchProtocol) {
  Bounds b;
  b.extend(glm::vec3(-1, 0, 2));
  b.extend(glm::vec3(3, 2, 6));
  const SceneCamera c = framing_camera(b);
  const float diag = std::sqrt(16.f + 4.f + 16.f);
  EXPECT_EQ(c.target, glm::vec3(1, 1, 4));
  EXPECT_NEAR(c.eye.x, 1.f, 0.f);
  EXPECT_NEAR(c.eye.y, 1.f, 0.f);
  EXPECT_NEAR(c.eye.z, 4.f + diag, 1e-5f);
  EXPECT_EQ(c.up, glm::vec3(0, 1, 0));
  EXPECT_EQ(c.vfov_degrees, 45.f);
}

}  // namespace
}  // namespace cohort
