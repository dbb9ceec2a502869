// What `cohort info` and `cohort render` say about a glTF material: every texture and what it
// drives, and a warning per feature the loader leaves out; one table of the material extensions'
// reference scenes, each listed, compiled and accepted as required.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_helpers.h"

namespace fs = std::filesystem;
using cohort_test::CommandResult;
using cohort_test::run;

namespace {

const fs::path kHelmet = fs::path(COHORT_SHARED_SCENES) / "damaged-helmet-gltf/DamagedHelmet.gltf";

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// `scene` with its first `from` made `to`, written to `out`, which it returns.
fs::path edited_copy(const fs::path& scene, const std::string& from, const std::string& to, const fs::path& out) {
  std::string text = cohort_test::read_all(scene);
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no " << from << " in " << scene;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  std::ofstream(out) << text;
  return out;
}

}  // namespace

TEST(GltfMaterialCli, InfoListsAllFiveHelmetTexturesAndWhatEachDrives) {
  if (!fs::exists(kHelmet)) GTEST_SKIP() << kHelmet << " not found";
  const CommandResult r = run("info " + kHelmet.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(count(r.output, "textures: 4 read, 1 not read\n"), 1u) << r.output;
  // the occlusion map: listed once with why it is not read, and no note or warning besides
  EXPECT_EQ(count(r.output, "  [not read] Default_AO.jpg: occlusion of 'Material_MR', not used: a path tracer traces "
                            "the occlusion it approximates\n"),
            1u)
      << r.output;
  EXPECT_EQ(count(r.output, "occlusion"), 2u) << r.output;
  EXPECT_EQ(count(r.output, "note: "), 0u) << r.output;
  EXPECT_EQ(count(r.output, "warning: "), 0u) << r.output;  // every other texture is honoured
  // every decoded texture with what it drives
  EXPECT_EQ(count(r.output, "Default_albedo.jpg 2048x2048, sRGB, bilinear, wrap repeat/repeat: base colour of "
                            "'Material_MR'"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "Default_metalRoughness.jpg 2048x2048, linear, bilinear, wrap repeat/repeat: metallic (B) "
                            "and roughness (G) of 'Material_MR'"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "Default_emissive.jpg 2048x2048, sRGB, bilinear, wrap repeat/repeat: emission of "
                            "'Material_MR'"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "Default_normal.jpg 2048x2048, linear, bilinear, wrap repeat/repeat: normals (scale 1) of "
                            "'Material_MR'"), 1u) << r.output;
}

// The shipped cut-out scene: info names the mode and cutoff, warns of nothing, and render compiles
// the alpha test; a mode glTF does not have is an input error naming the file.
TEST(GltfMaterialCli, AlphaModesAreListedCompiledAndChecked) {
  const std::string scene = (fs::path(COHORT_SOURCE_DIR) / "scenes/reference/alpha-mask.gltf").string();
  const CommandResult info = run("info " + scene);
  ASSERT_EQ(info.code, 0) << info.output;
  EXPECT_EQ(count(info.output, "alphaMode MASK (cutoff 0.3)"), 1u) << info.output;
  EXPECT_EQ(count(info.output, "glTF feature not honoured"), 0u) << info.output;
  cohort_test::TempDir dir;
  const CommandResult render = run("render " + scene + " --res 8x8 --spp 1 -v -o " + (dir.path / "a.exr").string());
  ASSERT_EQ(render.code, 0) << render.output;
  EXPECT_NE(render.output.find("kernel features: textures alpha\n"), std::string::npos) << render.output;
  const fs::path bad = edited_copy(scene, "\"MASK\"", "\"CUT\"", dir.path / "bad-alpha.gltf");
  const CommandResult rejected = run("info " + bad.string());
  EXPECT_EQ(rejected.code, 2) << rejected.output;
  EXPECT_NE(rejected.output.find(bad.string() + ": material 2 'panel': alphaMode \"CUT\" is not one of glTF 2.0's"),
            std::string::npos)
      << rejected.output;
}

// A triangle whose material asks for BLEND and an iridescence: one warning each, from info and from render.
TEST(GltfMaterialCli, InfoAndRenderWarnOnceForEachUnhonouredFeature) {
  cohort_test::TempDir dir;
  const fs::path scene = dir.path / "unhonoured.gltf";
  {
    std::ofstream out(scene);
    // positions (0,0,0) (1,0,0) (0,1,0) as little-endian floats, base64
    out << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_iridescence"],
      "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
      "materials": [{"alphaMode": "BLEND", "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_iridescence": {}}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
  }
  for (const std::string& command :
       {"info " + scene.string(), "render " + scene.string() + " --res 8x8 --spp 1 -o " + (dir.path / "u.exr").string()}) {
    const CommandResult r = run(command);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(count(r.output, "not honoured: alphaMode"), 0u) << r.output;  // BLEND is honoured
    EXPECT_EQ(count(r.output, "glTF feature not honoured: extension KHR_materials_iridescence: 1 material"), 1u) << r.output;
    EXPECT_EQ(count(r.output, "KHR_materials_iridescence"), 1u) << r.output;
  }
}

namespace {

// A material extension's reference scene (scenes/reference/): what `info` says of it (line fragments
// and how often each stands there), and the kernel features `render -v` compiles for it.
struct ExtensionScene {
  const char* name;
  const char* extension;
  const char* scene;
  std::vector<std::pair<std::string, std::size_t>> info;
  const char* kernel_features;
};

void PrintTo(const ExtensionScene& e, std::ostream* os) { *os << e.scene; }

const ExtensionScene kExtensionScenes[] = {
    {"Clearcoat", "KHR_materials_clearcoat", "clearcoat.gltf",
     {{", clearcoat 1 (roughness 0)", 2},
      {", clearcoat 1 (roughness 0.3)", 1},
      {"image 0 4x4, linear, nearest, wrap repeat/repeat: clearcoat factor (R) of 'textured'", 1}},
     "textures conductor clearcoat"},
    {"Specular", "KHR_materials_specular", "specular.gltf",
     {{"roughness 0.3, emission (0, 0, 0), specular 0.3 colour (3, 1.5, 0.5)\n", 1},
      {"roughness 0, emission (0, 0, 0), specular 1 colour (6, 3, 1.5)\n", 1},
      {"specular 1 colour (2, 2, 2), textured\n", 1},
      {"image 0 4x4, linear, nearest, wrap repeat/repeat: specular factor (A) of 'textured'", 1},
      {"image 1 4x4, sRGB, nearest, wrap repeat/repeat: specular colour (RGB) of 'textured'", 1}},
     "textures plastic specular"},
    {"Sheen", "KHR_materials_sheen", "sheen.gltf",
     {{"sheen (0.9, 0.5, 0.3) roughness 0.3\n", 1},
      {"sheen (0.9, 0.5, 0.3) roughness 0.8\n", 1},
      {"sheen (1, 1, 1) roughness 0.5, textured\n", 1},
      {"image 0 4x4, sRGB, nearest, wrap repeat/repeat: sheen colour (RGB) of 'sheen_tex'", 1}},
     "textures sheen"},
};

class GltfExtensionScene : public ::testing::TestWithParam<ExtensionScene> {};


// info names each material's extension and the textures with what they drive, and warns about
// nothing; render compiles the extension and says nothing of it, as shipped and with the extension
// required.
TEST_P(GltfExtensionScene, IsListedCompiledAndAcceptedAsRequired) {
  const ExtensionScene& e = GetParam();
  const fs::path scene = fs::path(COHORT_SOURCE_DIR) / "scenes/reference" / e.scene;
  const CommandResult info = run("info " + scene.string());
  ASSERT_EQ(info.code, 0) << info.output;
  EXPECT_EQ(count(info.output, "warning: "), 0u) << info.output;
  for (const auto& [line, times] : e.info) EXPECT_EQ(count(info.output, line), times) << line << " in:\n" << info.output;
  cohort_test::TempDir dir;
  const std::string extension = e.extension;
  const fs::path required = edited_copy(scene, "\"extensionsUsed\"",
                                        "\"extensionsRequired\": [\"" + extension + "\"], \"extensionsUsed\"",
                                        dir.path / "required.gltf");
  for (const fs::path& file : {scene, required}) {
    const CommandResult r = run("render " + file.string() + " --res 8x8 --spp 1 -v -o " + (dir.path / "r.exr").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(count(r.output, extension), 0u) << r.output;
    EXPECT_NE(r.output.find("kernel features: " + std::string(e.kernel_features) + "\n"), std::string::npos) << r.output;
  }
}

INSTANTIATE_TEST_SUITE_P(ReferenceScenes, GltfExtensionScene, ::testing::ValuesIn(kExtensionScenes),
                         [](const ::testing::TestParamInfo<ExtensionScene>& info) { return info.param.name; });

}  // namespace
