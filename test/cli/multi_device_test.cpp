// Several devices of one process (PoCL's POCL_DEVICES="pthread pthread" gives two identical CPU
// devices) render the single-device image bit for bit, share the passes, and resume bitwise.
#include <gtest/gtest.h>

#include <signal.h>

#include <nlohmann/json.hpp>

#include "cli/cli_helpers.h"

using namespace cohort_test;

namespace {

const std::string kTwoDevices = "POCL_DEVICES=pthread pthread";

std::string render_line(const fs::path& out, const std::string& method, const std::string& extra = "") {
  return std::string(COHORT_BINARY) + " render " + shipped_scene("cornell-box.gltf") +
         " --res 32x32 --spp 64 --pass-spp 1 --seed 5 --max-depth 6 --method " + method + " -o " + out.string() +
         // a pool of one sample per pixel: auto's screen (6 spp) is short enough to probe at 64 spp
         // where its share may be an eighth (COHORT_AUTO_PROBE_SHARE=8; a CPU's own rule is a 256th)
         " --wavefront-size 1024 " + extra;
}

// Skips (returns false) where the OpenCL platform does not give two devices for POCL_DEVICES.
bool two_devices_present() {
  const CommandResult r = run("devices", "env '" + kTwoDevices + "' ");
  return r.output.find("[1]") != std::string::npos;
}

}  // namespace

class TwoDevices : public ::testing::TestWithParam<const char*> {};

TEST_P(TwoDevices, GiveTheOneDeviceImageBitForBit) {
  if (!two_devices_present()) GTEST_SKIP() << "POCL_DEVICES=\"pthread pthread\" does not give two devices here";
  TempDir dir("cohort-multi-");
  const CommandResult one = run_shell("env COHORT_AUTO_PROBE_SHARE=8 " + render_line(dir.path / "one", GetParam()));
  ASSERT_EQ(one.code, 0) << one.output;
  const CommandResult two = run_shell("env COHORT_AUTO_PROBE_SHARE=8 '" + kTwoDevices + "' " +
                                      render_line(dir.path / "two", GetParam(),
                                                  "--device all --stats " + (dir.path / "two.json").string()));
  ASSERT_EQ(two.code, 0) << two.output;
  EXPECT_EQ(read_all(dir.path / "one.exr"), read_all(dir.path / "two.exr"));

  const auto stats = nlohmann::json::parse(read_all(dir.path / "two.json"));
  ASSERT_EQ(stats["devices"].size(), 2u);
  std::uint64_t passes = 0, rays = 0;
  for (const auto& d : stats["devices"]) {
    EXPECT_GT(d["passes"].get<int>(), 0) << "both devices take passes from the queue";
    EXPECT_GT(d["busy_seconds"].get<double>(), 0);
    passes += d["passes"].get<std::uint64_t>();
    rays += d["rays"].get<std::uint64_t>();
  }
  EXPECT_EQ(passes, 64u) << "64 spp at 32x32 is 64 passes of one sample";
  EXPECT_EQ(rays, stats["rays"].get<std::uint64_t>());
  if (std::string(GetParam()) == "auto") {
    // it probed (the reason is the probe's pick, or the default kept within the probe's noise)
    EXPECT_EQ(stats["auto"]["reason"].get<std::string>().find("too short"), std::string::npos) << stats["auto"];
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, TwoDevices, ::testing::Values("naive", "sc+rg", "pth", "auto"),
                         [](const auto& info) { return std::string(info.param) == "sc+rg" ? "sc_rg" : info.param; });

TEST(TwoDevicesCheckpoint, InterruptedAndResumedEqualsOneDevice) {
  if (!two_devices_present()) GTEST_SKIP() << "POCL_DEVICES=\"pthread pthread\" does not give two devices here";
  TempDir dir("cohort-multi-");
  const std::vector<std::string> args = {"render", shipped_scene("cornell-box.gltf"), "--res", "64x64", "--spp",
                                         "256", "--pass-spp", "4", "--seed", "9", "--device", "all", "-o", (dir.path / "part").string(),
                                         "--checkpoint", "0.05"};
  const CommandResult one = run("render " + shipped_scene("cornell-box.gltf") +
                                " --res 64x64 --spp 256 --pass-spp 4 --seed 9 -o " + (dir.path / "one").string());
  ASSERT_EQ(one.code, 0) << one.output;
  const pid_t pid = spawn(COHORT_BINARY, args, "", {kTwoDevices});
  wait_for_file(dir.path / "part.checkpoint");
  kill(pid, SIGINT);
  const int code = wait_exit(pid).value_or(-1);
  if (code == 0) GTEST_SKIP() << "the render finished before the interrupt arrived";
  EXPECT_EQ(code, 128 + SIGINT);

  auto resume = args;
  resume.push_back("--resume");
  ASSERT_EQ(wait_exit(spawn(COHORT_BINARY, resume, "", {kTwoDevices})).value_or(-1), 0);
  EXPECT_EQ(read_all(dir.path / "part.exr"), read_all(dir.path / "one.exr"));
}

TEST(DeviceList, NamesWhatIsWrong) {
  const CommandResult repeated = run("render " + shipped_scene("cornell-box.gltf") +
                                     " --res 8x8 --spp 1 --device 0,0 -o " +
                                     (fs::temp_directory_path() / "cohort-never-written").string());
  EXPECT_EQ(repeated.code, 2) << repeated.output;
  EXPECT_NE(repeated.output.find("listed twice"), std::string::npos) << repeated.output;
  const CommandResult unknown =
      run("render " + shipped_scene("cornell-box.gltf") + " --res 8x8 --spp 1 --device all:nosuchgpu");
  EXPECT_EQ(unknown.code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("nosuchgpu"), std::string::npos) << unknown.output;
}
