// Runs the cohort binary as a user would and checks exit codes, messages and outputs.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

struct CommandResult {
  int code = -1;
  std::string output;  // stdout and stderr
};

CommandResult run(const std::string& args) {
  const std::string cmd = std::string(COHORT_BINARY) + " " + args + " 2>&1";
  CommandResult r;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe.get())) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe.release());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cohort-cli-" + std::to_string(std::random_device{}()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::string scene(const std::string& name) { return std::string(COHORT_SOURCE_DIR) + "/scenes/" + name; }

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

TEST(Cli, BadEnvironmentMapIsExitTwoNamingTheFile) {
  TempDir dir;
  const fs::path garbage = dir.path / "not-really.exr";
  std::ofstream(garbage) << "this is not an OpenEXR file";
  for (const std::string& env : {garbage.string(), std::string("/nonexistent/sky.exr")}) {
    const CommandResult r =
        run("render " + scene("cornell-box.gltf") + " --res 8x8 --spp 1 --env " + env + " -o " + (dir.path / "o").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(fs::path(env).filename().string()), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path / "o.exr"));
  }
}

TEST(Cli, EnvironmentMapRendersAndInfoCountsPunctualLights) {
  TempDir dir;
  const std::string sky = std::string(COHORT_SOURCE_DIR) + "/scenes/reference/sky.exr";
  const CommandResult r = run("render " + scene("reference/envmap.gltf") + " --res 16x16 --spp 2 -v --env " + sky +
                              " -o " + (dir.path / "o").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("kernel features: envmap"), std::string::npos) << r.output;
  const CommandResult info = run("info " + scene("reference/punctual.gltf"));
  ASSERT_EQ(info.code, 0) << info.output;
  EXPECT_NE(info.output.find("1 point, 1 spot"), std::string::npos) << info.output;
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
