// Runs the cohort binary as a user would and checks exit codes, messages and outputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli/cli_helpers.h"

namespace fs = std::filesystem;
using cohort_test::CommandResult;
using cohort_test::TempDir;

namespace {

CommandResult run(const std::string& args) { return cohort_test::run_shell(std::string(COHORT_BINARY) + " " + args); }

std::string scene(const std::string& name) { return cohort_test::shipped_scene(name); }

}  // namespace

TEST(Cli, HelpAndVersionExitZero) {
  EXPECT_EQ(run("--help").code, 0);
  const CommandResult v = run("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.output.find("cohort"), std::string::npos);
}

TEST(Cli, MissingSceneFileIsExitTwoNamingTheFile) {
  const CommandResult r = run("render /nonexistent/nothing-here.gltf");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing-here.gltf"), std::string::npos) << r.output;
}

TEST(Cli, UnknownOptionIsExitTwo) {
  const CommandResult r = run("render " + scene("cornell-box.gltf") + " --no-such-option");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("no-such-option"), std::string::npos) << r.output;
}

TEST(Cli, BadResolutionIsExitTwo) {
  for (const char* res : {"0x10", "abc", "10x", "100000x10", "-5x5"}) {
    const CommandResult r = run("render " + scene("cornell-box.gltf") + " --res " + res);
    EXPECT_EQ(r.code, 2) << res << ": " << r.output;
    EXPECT_NE(r.output.find("--res"), std::string::npos) << r.output;
  }
}

TEST(Cli, UnknownMethodAndMissingCommandAreExitTwo) {
  EXPECT_EQ(run("render " + scene("cornell-box.gltf") + " --method teleport").code, 2);
  EXPECT_EQ(run("").code, 2);
}

TEST(Cli, RenderWritesExrPngAndStats) {
  TempDir dir;
  const CommandResult r = run("render " + scene("cornell-box.gltf") + " --res 24x16 --spp 2 -o " + (dir.path / "box").string() +
                    " --stats " + (dir.path / "stats.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir.path / "box.exr"));
  EXPECT_TRUE(fs::exists(dir.path / "box.png"));
  std::ifstream in(dir.path / "stats.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["image"]["spp"], 2);
  EXPECT_GT(j["rays"].get<double>(), 24 * 16 * 2);
  EXPECT_GT(j["rays_per_second"].get<double>(), 0);
  EXPECT_TRUE(j["kernels"].contains("render_naive"));
  // only the outputs: no temporary file is left behind
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 3);
}

TEST(Cli, AFailedRunLeavesEarlierOutputsUntouched) {
  TempDir dir;
  const fs::path exr = dir.path / "keep.exr";
  std::ofstream(exr) << "earlier result";
  const CommandResult r = run("render /nonexistent.gltf -o " + exr.string());
  EXPECT_EQ(r.code, 2);
  std::ifstream in(exr);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "earlier result");
}

TEST(Cli, OutputIntoAMissingDirectoryFailsBeforeRendering) {
  const CommandResult r = run("render " + scene("cornell-box.gltf") + " -o /nonexistent-dir/x.exr");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("nonexistent-dir"), std::string::npos) << r.output;
}

TEST(Cli, InfoPrintsSceneAndTree) {
  const CommandResult r = run("info " + scene("cornell-box.gltf"));
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* word : {"triangles:", "materials:", "lights:", "bounds:", "kd-tree:", "memory:"})
    EXPECT_NE(r.output.find(word), std::string::npos) << word << "\n" << r.output;
}

TEST(Cli, DevicesListsPocl) {
  const CommandResult r = run("devices");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("compute units"), std::string::npos) << r.output;
}

TEST(Cli, ASceneThatDoesNotFitTheDeviceFailsWithTheSizes) {
  TempDir dir;
  const CommandResult r = run("render " + scene("furnace-sphere.gltf") + " --res 8x8 --spp 1 --memory-limit 0.01 -o " +
                              (dir.path / "x").string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("bytes"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path / "x.exr"));
}

TEST(Cli, TimeLimitStopsTheRender) {
  TempDir dir;
  const CommandResult r = run("render " + scene("cornell-box.gltf") + " --res 16x16 --spp 0 --time 0.5 -o " +
                              (dir.path / "t").string() + " --stats " + (dir.path / "t.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir.path / "t.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_GT(j["image"]["spp"].get<int>(), 0);
  EXPECT_GE(j["timings"]["render_seconds"].get<double>(), 0.5);
  EXPECT_EQ(run("render " + scene("cornell-box.gltf") + " --spp 0").code, 2);  // --spp 0 needs --time
}
