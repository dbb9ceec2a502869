// What `cohort info` and `cohort render` say about a glTF material: every texture and what it
// drives, and a warning per feature the loader leaves out.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

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

}  // namespace

TEST(GltfMaterialCli, InfoNamesOcclusionOnceAndWarnsPerUnhonouredFeature) {
  if (!fs::exists(kHelmet)) GTEST_SKIP() << kHelmet << " not found";
  const CommandResult r = run("info " + kHelmet.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(count(r.output, "occlusionTexture"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "note: "), 1u) << r.output;
  EXPECT_EQ(count(r.output, "warning: "), count(r.output, "glTF feature not honoured")) << r.output;
  EXPECT_EQ(count(r.output, "normalTexture"), 1u) << r.output;
  // every decoded texture with what it drives
  EXPECT_EQ(count(r.output, "Default_albedo.jpg 2048x2048, sRGB, bilinear, wrap repeat/repeat: base colour of "
                            "'Material_MR'"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "Default_metalRoughness.jpg 2048x2048, linear, bilinear, wrap repeat/repeat: metallic (B) "
                            "and roughness (G) of 'Material_MR'"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "Default_emissive.jpg 2048x2048, sRGB, bilinear, wrap repeat/repeat: emission of "
                            "'Material_MR'"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "metallicRoughnessTexture"), 0u) << r.output;  // honoured: no warning
}

TEST(GltfMaterialCli, RenderWarnsOnceForEachUnhonouredFeature) {
  if (!fs::exists(kHelmet)) GTEST_SKIP() << kHelmet << " not found";
  cohort_test::TempDir dir;
  const CommandResult r =
      run("render " + kHelmet.string() + " --res 8x8 --spp 1 --method naive -o " + (dir.path / "h.exr").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(count(r.output, "normalTexture"), 1u) << r.output;
  EXPECT_EQ(count(r.output, "occlusionTexture"), 0u) << r.output;  // said by info only
}
