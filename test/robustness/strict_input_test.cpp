// The strict readers (docs/input.md): gzip read to its end, numbers read whole, glTF versions and
// required extensions, node transforms. The CLI's view of the same cases (exit 2, no image) is the
// malformed-input corpus in test/data/bad-input (bad_input_test.cpp, beside this file).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "runtime/scene/gzip_file.h"
#include "runtime/scene/scene.h"
#include "runtime/scene/strict_number.h"
#include "runtime/util/error.h"
#include "scene/scene_test_util.h"

namespace cohort {
namespace {

using nlohmann::json;
using test::expect_input_error;
using test::GltfWriter;
using test::TempDir;

const std::string kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// Writes `text` as `name` in `dir` and expects loading it to fail with `what` in the message.
void rejects(const TempDir& dir, const std::string& name, const std::string& text, const std::string& what) {
  test::write_file(dir / name, text);
  expect_input_error(dir / name, what);
}

TEST(StrictNumber, WholeTokenOrNothing) {
  EXPECT_EQ(parse_number("-1.5e3"), -1500.0);
  EXPECT_EQ(parse_number("+.25"), 0.25);
  EXPECT_EQ(parse_number("7."), 7.0);
  EXPECT_TRUE(std::isnan(*parse_number("nan")));
  EXPECT_EQ(parse_number("-inf"), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse_number("1e999"), std::numeric_limits<double>::infinity());  // beyond double: infinite
  EXPECT_EQ(parse_number("1e-999"), 0.0);
  for (const char* bad : {"", "1.5abc", "0x10", "1,5", "--1", "+-1", "1e", "+", ".", "1 ", "one"})
    EXPECT_FALSE(parse_number(bad)) << bad;
  EXPECT_EQ(parse_integer("+3"), 3);
  EXPECT_EQ(parse_integer("-12"), -12);
  for (const char* bad : {"2.0", "2e1", "", "3x", "99999999999999999999"}) EXPECT_FALSE(parse_integer(bad)) << bad;
}

// Every proper prefix of a gzip file lacks at least its trailer: each must fail, none may return
// what it inflated so far.
TEST(StrictGzip, EveryCutFailsAsTruncated) {
  TempDir dir;
  std::string text;
  for (int i = 0; i < 300; ++i) text += "v " + std::to_string(i) + " " + std::to_string(i * 7 % 13) + " 0\n";
  test::write_gzip(dir / "whole.obj.gz", text);
  const std::string gz = test::read_file(dir / "whole.obj.gz");
  EXPECT_EQ(read_whole_file(dir / "whole.obj.gz"), text);
  for (std::size_t keep = 0; keep < gz.size(); ++keep) {
    test::write_file(dir / "cut.obj.gz", gz.substr(0, keep));
    try {
      const std::string read = read_whole_file(dir / "cut.obj.gz");
      ADD_FAILURE() << "cut at " << keep << " of " << gz.size() << " bytes read " << read.size() << " bytes";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("cut.obj.gz"), std::string::npos) << message;
      EXPECT_NE(message.find("truncated"), std::string::npos) << "cut at " << keep << ": " << message;
    }
  }
}

TEST(StrictGzip, TrailerMismatchIsCorruptAndMembersConcatenate) {
  TempDir dir;
  test::write_gzip(dir / "a.gz", "first ");
  test::write_gzip(dir / "b.gz", "second");
  const std::string a = test::read_file(dir / "a.gz"), b = test::read_file(dir / "b.gz");
  test::write_file(dir / "joined.gz", a + b + std::string(16, '\0'));  // zero padding after the last member
  EXPECT_EQ(read_whole_file(dir / "joined.gz"), "first second");
  for (std::size_t from_end : {8u, 4u}) {  // a CRC byte, a length byte
    std::string bad = a;
    bad[bad.size() - from_end] ^= 0x40;
    test::write_file(dir / "bad.gz", bad);
    EXPECT_THROW(
        {
          try {
            read_whole_file(dir / "bad.gz");
          } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("corrupt"), std::string::npos) << e.what();
            throw;
          }
        },
        InputError);
  }
}

TEST(StrictObj, NumbersAreReadWholeAndErrorsNameTheLine) {
  TempDir dir;
  rejects(dir, "suffix.obj", "v 0 0 0\nv 1 0 0\nv 0 1.5abc 0\nf 1 2 3\n", "line 3: '1.5abc'");
  rejects(dir, "short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2: vertex has 2 numbers");
  rejects(dir, "face.obj", kTriangleObj + "# two\nf 1 2 3z\n", "line 6: face corner '3z'");
  rejects(dir, "zero.obj", kTriangleObj + "f 0 1 2\n", "line 5: face index 0");
  rejects(dir, "vt.obj", kTriangleObj + "vt 0.5 0.5e\n", "'0.5e'");
  // Line ends, comments, signs and v//n corners stay legal.
  test::write_file(dir / "fine.obj",
                   "v +0 0 0 # origin\r\nv 1. 0 0\rv 0 .5e1 0\nvn 0 0 1\nvt 0\nf 1/1/1 2//1 -1/1\n");
  const Scene s = load_scene(dir / "fine.obj");
  ASSERT_EQ(s.positions.size(), 3u);
  EXPECT_EQ(s.positions[2], glm::vec3(0, 5, 0));
}

// tinyobjloader reads "nan" and "inf" as 0, which would move the vertex to the origin; they must
// reach the scene as they are so the triangle is dropped, not drawn somewhere else.
TEST(StrictObj, NonFiniteCoordinatesReachTheScene) {
  TempDir dir;
  test::write_file(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 2 inf\nvt nan 0\nf 1 2 3\nf 1/1 2/1 4/1\n");
  const Scene s = load_scene(dir / "nan.obj");
  ASSERT_EQ(s.positions.size(), 6u);
  EXPECT_TRUE(std::isnan(s.positions[5].x));
  EXPECT_EQ(s.positions[5].y, 2.f);
  EXPECT_TRUE(std::isinf(s.positions[5].z));
  ASSERT_EQ(s.uvs.size(), 6u);
  EXPECT_TRUE(std::isnan(s.uvs[5].x));
}

std::string ascii_ply(const std::string& body, int vertices = 3, int faces = 1) {
  return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n" + body;
}

TEST(StrictPly, AsciiItemsAreOneLineOfTheDeclaredTypes) {
  TempDir dir;
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  test::write_file(dir / "ok.ply", ascii_ply(vertices + "3 0 1 2\n\n"));
  EXPECT_EQ(load_scene(dir / "ok.ply").triangle_count(), 1u);
  rejects(dir, "suffix.ply", ascii_ply("0 0 0\n1 0 0x\n0 1 0\n3 0 1 2\n"), "line 11: bad number '0x'");
  rejects(dir, "extra.ply", ascii_ply("0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n"),
          "line 10: more values than the header declares for a 'vertex'");
  rejects(dir, "short.ply", ascii_ply("0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "line 10: the line ends");
  rejects(dir, "more.ply", ascii_ply(vertices + "3 0 1 2\n3 2 1 0\n"), "line 14: data after the last element");
  rejects(dir, "count.ply", ascii_ply(vertices + "3.0 0 1 2\n"), "'3.0' is not a 1-byte unsigned integer");
  rejects(dir, "index.ply", ascii_ply(vertices + "3 0 1 4294967296\n"), "not a 4-byte signed integer");
}

GltfWriter triangle_scene() {
  GltfWriter g;
  const int pos = g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  g.roots({g.node({{"mesh", g.mesh(pos)}})});
  return g;
}

TEST(StrictGltf, VersionsAndRequiredExtensions) {
  TempDir dir;
  for (const char* version : {"2.0", "2.1", "2.10"}) {
    GltfWriter g = triangle_scene();
    g.doc()["asset"]["version"] = version;
    EXPECT_EQ(load_scene(g.write_gltf(dir.path(), "v")).triangle_count(), 1u) << version;
  }
  for (const char* version : {"1.0", "3.0", "2", "2.", "2.0.1", "x2.0", "02.0a"}) {
    GltfWriter g = triangle_scene();
    g.doc()["asset"]["version"] = version;
    expect_input_error(g.write_gltf(dir.path(), "v"), "asset.version");
  }
  GltfWriter min = triangle_scene();
  min.doc()["asset"]["minVersion"] = "2.0";
  EXPECT_EQ(load_scene(min.write_gltf(dir.path(), "min")).triangle_count(), 1u);
  min.doc()["asset"]["minVersion"] = "2.1";
  expect_input_error(min.write_gltf(dir.path(), "min"), "minVersion '2.1'");

  GltfWriter ext = triangle_scene();
  ext.doc()["extensionsUsed"] = ext.doc()["extensionsRequired"] =
      json::array({"KHR_materials_emissive_strength", "KHR_lights_punctual", "KHR_mesh_quantization"});
  EXPECT_EQ(load_scene(ext.write_gltf(dir.path(), "ext")).triangle_count(), 1u);
  ext.doc()["extensionsRequired"].push_back("KHR_texture_transform");  // implemented
  EXPECT_EQ(load_scene(ext.write_gltf(dir.path(), "ext")).triangle_count(), 1u);
  ext.doc()["extensionsRequired"].push_back("EXT_texture_webp");
  expect_input_error(ext.write_gltf(dir.path(), "ext"), "EXT_texture_webp");
}

TEST(StrictGltf, NodeTransformsOutsideTheSpecificationAreErrors) {
  TempDir dir;
  const auto with_node = [&](const json& fields) {
    GltfWriter g = triangle_scene();
    for (const auto& [key, value] : fields.items()) g.doc()["nodes"][0][key] = value;
    return g.write_gltf(dir.path(), "node");
  };
  expect_input_error(with_node({{"scale", {1, 1}}}), "node 0 scale has 2 numbers, not 3");
  expect_input_error(with_node({{"matrix", json::array({1, 0, 0, 1})}}), "matrix has 4 numbers");
  expect_input_error(with_node({{"rotation", {0, 0, 0, 0}}}), "not a unit quaternion");
  expect_input_error(with_node({{"rotation", {0, 0, 0, 2}}}), "not a unit quaternion");
  expect_input_error(with_node({{"matrix", {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}}), "not affine");
  // A quaternion rounded by an exporter is still a rotation; a zero scale loads, with a warning.
  EXPECT_EQ(load_scene(with_node({{"rotation", {0, 0, 0.7071, 0.7071}}})).triangle_count(), 1u);
  const Scene hidden = load_scene(with_node({{"scale", {0, 0, 0}}}));
  EXPECT_TRUE(std::any_of(hidden.warnings.begin(), hidden.warnings.end(), [](const std::string& w) {
    return w.find("node 0 has a singular transform") != std::string::npos;
  }));
}

TEST(StrictGltf, SparseAccessorsStayInside) {
  TempDir dir;
  const auto with_sparse = [&](int index_type, std::uint32_t index, int count) {
    GltfWriter g = triangle_scene();
    const std::uint32_t indices[1] = {index};
    const float values[3] = {5, 5, 5};
    const int iv = g.view(indices, sizeof indices);
    const int vv = g.view(values, sizeof values);
    g.doc()["accessors"][0]["sparse"] = {{"count", count},
                                         {"indices", {{"bufferView", iv}, {"componentType", index_type}}},
                                         {"values", {{"bufferView", vv}}}};
    return g.write_gltf(dir.path(), "sparse");
  };
  EXPECT_EQ(load_scene(with_sparse(5125, 2, 1)).positions[2], glm::vec3(5.f));
  expect_input_error(with_sparse(5125, 3, 1), "substitutes element 3 of 3");
  expect_input_error(with_sparse(5126, 0, 1), "not unsigned integers");
  expect_input_error(with_sparse(5125, 0, -1));
}

TEST(StrictMtl, NumbersAreReadWholeAndFinite) {
  TempDir dir;
  const std::string obj = "mtllib lib.mtl\nusemtl m\n" + kTriangleObj;
  test::write_file(dir / "m.obj", obj);
  test::write_file(dir / "lib.mtl", "newmtl m\nKd 0.5 0.5 0.5 # grey\nKa xyz 0 0 0\nd -halo 0.5\nKe 1\n");
  const Scene ok = load_scene(dir / "m.obj");
  EXPECT_EQ(ok.materials[0].base_color, glm::vec3(0.5f));
  EXPECT_EQ(ok.materials[0].emission, glm::vec3(1.f));
  for (const auto& [mtl, what] : {std::pair{"newmtl m\nKd 0.5 0.5abc 0.5\n", "line 2: '0.5abc' in Kd"},
                                  std::pair{"newmtl m\n\nKe nan 1 1\n", "line 3: 'nan' in Ke is not a finite"},
                                  std::pair{"newmtl m\nNs\n", "line 2: Ns has 0 numbers"},
                                  std::pair{"newmtl m\nKd 1 1\n", "line 2: Kd has 2 numbers"}}) {
    test::write_file(dir / "lib.mtl", mtl);
    try {
      load_scene(dir / "m.obj");
      ADD_FAILURE() << mtl << " loaded";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("m.obj: material library "), std::string::npos) << message;
      EXPECT_NE(message.find("lib.mtl: " + std::string(what)), std::string::npos) << message;
    }
  }
}

TEST(StrictGltf, DefaultSceneMustExistAndIgnoredExtensionsAreNamed) {
  TempDir dir;
  GltfWriter g = triangle_scene();
  g.doc()["scene"] = 3;
  expect_input_error(g.write_gltf(dir.path(), "scene"), "scene 3 does not exist");
  GltfWriter used = triangle_scene();
  used.doc()["extensionsUsed"] = json::array({"KHR_materials_emissive_strength", "EXT_texture_webp"});
  const Scene s = load_scene(used.write_gltf(dir.path(), "used"));
  EXPECT_TRUE(std::any_of(s.warnings.begin(), s.warnings.end(), [](const std::string& w) {
    return w.find("ignored (optional, not implemented): EXT_texture_webp") != std::string::npos;
  }));
}

TEST(StrictMaterials, NonFiniteOrNegativeFactorsAreErrors) {
  TempDir dir;
  test::write_file(dir / "m.mtl", "newmtl m\nKd 0.5 1e39 0.5\n");
  rejects(dir, "m.obj", "mtllib m.mtl\nusemtl m\n" + kTriangleObj, "material 0 'm': base colour");
  GltfWriter g = triangle_scene();
  g.doc()["meshes"][0]["primitives"][0]["material"] = g.material({{"emissiveFactor", {1, -1, 1}}});
  expect_input_error(g.write_gltf(dir.path(), "emit"), "emission");
}

// glTF 2.0: alphaMode is OPAQUE (the default), MASK or BLEND; alphaCutoff (default 0.5, minimum 0)
// is read with MASK and ignored otherwise; above 1 it is valid and cuts the whole material out.
TEST(StrictMaterials, AlphaModeAndCutoffFollowTheSpecification) {
  TempDir dir;
  const auto with = [&](const json& material, const std::string& name) {
    GltfWriter g = triangle_scene();
    g.doc()["meshes"][0]["primitives"][0]["material"] = g.material(material);
    return g.write_gltf(dir.path(), name);
  };
  expect_input_error(with({{"name", "leaf"}, {"alphaMode", "CUTOUT"}}, "mode"),
                     "material 0 'leaf': alphaMode \"CUTOUT\" is not one of glTF 2.0's OPAQUE, MASK and BLEND");
  expect_input_error(with({{"alphaMode", "mask"}}, "lower"), "alphaMode \"mask\"");
  expect_input_error(with({{"alphaMode", "MASK"}, {"alphaCutoff", -0.25}}, "cutoff"), "alphaCutoff -0.25 is negative");
  const auto loaded = [&](const json& material) { return load_scene(with(material, "ok")).materials.at(0); };
  EXPECT_EQ(loaded(json::object()).alpha_mode, AlphaMode::opaque);
  const SceneMaterial mask = loaded({{"alphaMode", "MASK"}});
  EXPECT_EQ(mask.alpha_mode, AlphaMode::mask);
  EXPECT_EQ(mask.alpha_cutoff, 0.5f);
  EXPECT_EQ(loaded({{"alphaMode", "MASK"}, {"alphaCutoff", 0.0}}).alpha_cutoff, 0.f);
  EXPECT_EQ(loaded({{"alphaMode", "MASK"}, {"alphaCutoff", 1.5}}).alpha_cutoff, 1.5f);
  const SceneMaterial blend = loaded({{"alphaMode", "BLEND"}, {"alphaCutoff", -3}});  // ignored outside MASK
  EXPECT_EQ(blend.alpha_mode, AlphaMode::blend);
  EXPECT_EQ(blend.alpha_cutoff, 0.5f);
  EXPECT_EQ(loaded({{"alphaMode", "OPAQUE"}, {"alphaCutoff", -1}}).alpha_mode, AlphaMode::opaque);
}

}  // namespace
}  // namespace cohort
