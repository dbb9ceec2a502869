// OBJ + MTL loading on files written by the test.
#include <gtest/gtest.h>

#include "runtime/scene/scene.h"
#include "scene_test_util.h"

namespace cohort {
namespace {

using test::TempDir;

const char* kPentagonObj =
    "mtllib shapes.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1.5 1 0\nv 0.5 2 0\nv -0.5 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
    "usemtl lamp\n"
    "f 1/1 2/2 3/3 4/4 5/5\n"
    "usemtl nothing_by_that_name\n"
    "f -5 -3 -1\n";

TEST(Obj, PolygonsFanAndMaterialsMap) {
  TempDir dir;
  test::write_file(dir / "shapes.obj", kPentagonObj);
  test::write_file(dir / "shapes.mtl", "newmtl lamp\nKd 0.1 0.2 0.3\nKe 4 5 6\nd 0.5\n");
  const Scene s = load_scene(dir / "shapes.obj");
  ASSERT_EQ(s.triangle_count(), 4u);  // pentagon -> 3, plus one triangle
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "lamp");
  EXPECT_EQ(s.materials[0].base_color, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.materials[0].emission, glm::vec3(4, 5, 6));
  EXPECT_EQ(s.materials[0].alpha, 0.5f);
  EXPECT_EQ(s.materials[1].name, "default");  // usemtl of an unknown material
  EXPECT_EQ(s.material_ids, (std::vector<std::uint32_t>{0, 0, 0, 1}));
  EXPECT_EQ(s.emissive_triangle_count(), 3u);
  // Fan from the first corner, negative indices relative to the end.
  EXPECT_EQ(s.positions[3], glm::vec3(0, 0, 0));
  EXPECT_EQ(s.positions[4], glm::vec3(1.5f, 1, 0));
  EXPECT_EQ(s.positions[5], glm::vec3(0.5f, 2, 0));
  EXPECT_EQ(s.positions[10], glm::vec3(1.5f, 1, 0));
  // OBJ's v runs up the image; Scene::uvs run down it. The last triangle has no uvs: zeros.
  ASSERT_EQ(s.uvs.size(), 12u);
  EXPECT_EQ(s.uvs[1], glm::vec2(1, 1));
  EXPECT_EQ(s.uvs[2], glm::vec2(1, 0));
  EXPECT_EQ(s.uvs[11], glm::vec2(0));
}

TEST(Obj, MissingMaterialLibraryIsAWarning) {
  TempDir dir;
  test::write_file(dir / "lonely.obj", kPentagonObj);
  const Scene s = load_scene(dir / "lonely.obj");
  EXPECT_EQ(s.triangle_count(), 4u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  bool warned = false;
  for (const auto& w : s.warnings) warned |= w.find("shapes.mtl") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Obj, CompressedObjReadsItsMtlBesideIt) {
  TempDir dir;
  test::write_gzip(dir / "shapes.obj.gz", kPentagonObj);
  test::write_file(dir / "shapes.mtl", "newmtl lamp\nKd 1 1 1\nKe 1 1 1\n");
  const Scene s = load_scene(dir / "shapes.obj.gz");
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_EQ(s.emissive_triangle_count(), 3u);
}

TEST(Obj, ConcatenatedGzipMembersReadAsOneFile) {
  TempDir dir;
  test::write_gzip(dir / "a.gz", "v 0 0 0\nv 1 0 0\n");
  test::write_gzip(dir / "b.gz", "v 0 1 0\nf 1 2 3\n");
  test::write_file(dir / "joined.obj.gz", test::read_file(dir / "a.gz") + test::read_file(dir / "b.gz"));
  EXPECT_EQ(load_scene(dir / "joined.obj.gz").triangle_count(), 1u);
}

TEST(Obj, TextureFoundIgnoringLetterCase) {
  TempDir dir;
  test::write_file(dir / "wall.ppm", std::string("P6\n1 1\n255\n") + std::string("\x10\x20\x30", 3));
  test::write_file(dir / "t.obj",
                   "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                   "usemtl wall\nf 1/1 2/2 3/3\n");
  test::write_file(dir / "t.mtl", "newmtl wall\nKd 1 1 1\nmap_Kd WALL.PPM\n");
  const Scene s = load_scene(dir / "t.obj");
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.materials[0].base_color_texture, 0);
  EXPECT_EQ(s.textures[0].rgba, (std::vector<std::uint8_t>{0x10, 0x20, 0x30, 0xff}));
}

TEST(Obj, OutOfRangeIndexIsAnError) {
  TempDir dir;
  test::write_file(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  test::expect_input_error(dir / "range.obj", "out of range");
  test::write_file(dir / "relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n");
  test::expect_input_error(dir / "relative.obj", "out of range");
  test::write_file(dir / "texcoord.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n");
  test::expect_input_error(dir / "texcoord.obj", "texture coordinate");
}

TEST(Obj, EmptyObjIsAnError) {
  TempDir dir;
  test::write_file(dir / "empty.obj", "");
  test::expect_input_error(dir / "empty.obj", "no triangles");
  test::write_file(dir / "points.obj", "v 0 0 0\nv 1 0 0\np 1 2\n");
  test::expect_input_error(dir / "points.obj", "no triangles");
}

}  // namespace
}  // namespace cohort
