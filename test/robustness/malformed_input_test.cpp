// The loaders on bad input of every kind: InputError naming the file; nothing crashes. The CLI's
// view of the malformed-input corpus is bad_input_test.cpp, beside this file.
#include <gtest/gtest.h>

#include "runtime/scene/scene.h"
#include "scene/scene_test_util.h"

namespace cohort {
namespace {

using test::expect_input_error;
using test::GltfWriter;
using test::TempDir;

GltfWriter triangle_gltf(const std::vector<std::uint16_t>& indices) {
  GltfWriter g;
  const int pos = g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  g.roots({g.node({{"mesh", g.mesh(pos, g.indices(indices), -1, 4, "broken_mesh")}})});
  return g;
}

TEST(MalformedInput, MissingFile) {
  TempDir dir;
  expect_input_error(dir / "nowhere.gltf", "no such file");
  expect_input_error(dir / "nowhere.obj.gz", "no such file");
}

TEST(MalformedInput, UnknownExtension) {
  TempDir dir;
  test::write_file(dir / "model.fbx", "Kaydara FBX Binary");
  expect_input_error(dir / "model.fbx", "unknown scene format");
  test::write_file(dir / "noext", "x");
  expect_input_error(dir / "noext", "unknown scene format");
}

TEST(MalformedInput, ExtensionsAreCaseInsensitive) {
  TempDir dir;
  test::write_file(dir / "LOUD.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(load_scene(dir / "LOUD.OBJ").triangle_count(), 1u);
}

TEST(MalformedInput, TruncatedGlb) {
  TempDir dir;
  std::string glb = triangle_gltf({0, 1, 2}).glb_bytes();
  for (std::size_t keep : {glb.size() / 2, std::size_t{30}, std::size_t{12}, glb.size() - 4}) {
    test::write_file(dir / "cut.glb", glb.substr(0, keep));
    expect_input_error(dir / "cut.glb");
  }
  // A BIN chunk whose length runs past the end of the file.
  std::string lying = glb;
  const std::size_t json_length =
      static_cast<unsigned char>(lying[12]) | static_cast<unsigned char>(lying[13]) << 8;
  lying[20 + json_length] = '\x7f';
  test::write_file(dir / "lying.glb", lying);
  expect_input_error(dir / "lying.glb");
}

TEST(MalformedInput, GarbageGltf) {
  TempDir dir;
  test::write_file(dir / "garbage.gltf", "{ this is not json");
  expect_input_error(dir / "garbage.gltf", "invalid glTF");
  test::write_file(dir / "garbage.glb", std::string(64, 'x'));
  expect_input_error(dir / "garbage.glb");
}

TEST(MalformedInput, GltfIndexOutOfRangeNamesTheMesh) {
  TempDir dir;
  expect_input_error(triangle_gltf({0, 1, 3}).write_gltf(dir.path(), "range"), "broken_mesh");
}

TEST(MalformedInput, GltfAccessorOverrunningItsBufferView) {
  TempDir dir;
  GltfWriter g = triangle_gltf({0, 1, 2});
  g.doc()["accessors"][0]["count"] = 1000000;
  expect_input_error(g.write_gltf(dir.path(), "overrun"), "overruns");
  GltfWriter h = triangle_gltf({0, 1, 2});
  h.doc()["accessors"][1]["byteOffset"] = 1u << 31;
  expect_input_error(h.write_gltf(dir.path(), "offset"), "overruns");
  GltfWriter k = triangle_gltf({0, 1, 2});
  k.doc()["bufferViews"][0]["byteLength"] = 1u << 30;
  expect_input_error(k.write_gltf(dir.path(), "view"));
}

TEST(MalformedInput, GltfCyclicNodes) {
  TempDir dir;
  GltfWriter g = triangle_gltf({0, 1, 2});
  g.doc()["nodes"][0]["children"] = {1};
  g.node({{"children", {0}}});
  expect_input_error(g.write_gltf(dir.path(), "cycle"), "cyclic");
}

TEST(MalformedInput, GltfDeepHierarchy) {
  TempDir dir;
  GltfWriter g = triangle_gltf({0, 1, 2});
  for (int i = 1; i < 1000; ++i) g.node({{"children", {i - 1}}});
  g.roots({999});
  expect_input_error(g.write_gltf(dir.path(), "deep"), "deeper");
}

TEST(MalformedInput, GltfSharedSubtreesCannotExplode) {
  TempDir dir;
  GltfWriter g = triangle_gltf({0, 1, 2});
  // Each level's node has two children that are both the next level's node: 2^30 paths.
  int below = g.node(nlohmann::json::object());
  for (int level = 0; level < 30; ++level) below = g.node({{"children", {below, below}}});
  g.roots({0, below});
  expect_input_error(g.write_gltf(dir.path(), "dag"), "node instances");
}

TEST(MalformedInput, GltfBadReferences) {
  TempDir dir;
  GltfWriter g = triangle_gltf({0, 1, 2});
  g.doc()["meshes"][0]["primitives"][0]["material"] = 7;
  expect_input_error(g.write_gltf(dir.path(), "material"), "material 7");
  GltfWriter h = triangle_gltf({0, 1, 2});
  h.roots({5});
  expect_input_error(h.write_gltf(dir.path(), "node"), "node 5");
}

TEST(MalformedInput, EmptyGltf) {
  TempDir dir;
  test::write_file(dir / "empty.gltf", R"({"asset": {"version": "2.0"}})");
  expect_input_error(dir / "empty.gltf", "no triangles");
}

TEST(MalformedInput, CorruptAndTruncatedGzip) {
  TempDir dir;
  using namespace std::string_literals;
  test::write_file(dir / "corrupt.obj.gz",
                   "\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03 not deflate data at all"s);
  expect_input_error(dir / "corrupt.obj.gz", "gzip");
  test::write_file(dir / "plain.ply.gz", "ply\nformat ascii 1.0\n");
  expect_input_error(dir / "plain.ply.gz", "gzip");
  test::write_gzip(dir / "whole.obj.gz", std::string(50000, '#') + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string gz = test::read_file(dir / "whole.obj.gz");
  test::write_file(dir / "cut.obj.gz", gz.substr(0, gz.size() / 2));
  expect_input_error(dir / "cut.obj.gz", "gzip");
  test::write_file(dir / "empty.obj.gz", "");
  expect_input_error(dir / "empty.obj.gz", "gzip");
}

}  // namespace
}  // namespace cohort
