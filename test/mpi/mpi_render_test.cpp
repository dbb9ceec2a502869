// `mpirun -np 2 cohort render` gives the single-process image bit for bit; a rank that dies or
// fails ends the job with a message naming the rank and host; a resumed job gives the same image.
// Skips where mpirun is missing or cohort was built without MPI.
#include <gtest/gtest.h>

#include <cstdlib>
#include <signal.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli/cli_helpers.h"

using namespace cohort_test;

namespace {

std::string skip_reason() {
#ifndef COHORT_TEST_MPI
  return "cohort was built without MPI (apt-get install openmpi-bin libopenmpi-dev)";
#else
  if (run_shell("command -v mpirun").code != 0) return "mpirun is not installed (apt-get install openmpi-bin)";
  return "";
#endif
}

// mpirun with two ranks on this machine: oversubscribed (2 cores), and allowed as root in CI.
std::vector<std::string> mpirun_args(const std::vector<std::string>& cohort_args) {
  std::vector<std::string> a = {"-np", "2", "--oversubscribe"};
  if (geteuid() == 0) a.push_back("--allow-run-as-root");
  if (std::getenv("COHORT_AUTO_PROBE_SHARE")) a.insert(a.end(), {"-x", "COHORT_AUTO_PROBE_SHARE"});
  a.push_back(COHORT_BINARY);
  a.insert(a.end(), cohort_args.begin(), cohort_args.end());
  return a;
}

// Passes of `pass_spp` samples per pixel: many passes, so both ranks take some and a kill lands between two.
std::vector<std::string> render_args(const fs::path& out, const std::string& method, const std::string& spp,
                                     const std::string& pass_spp = "1") {
  return {"render", shipped_scene("cornell-box.gltf"), "--res", "64x64", "--spp", spp, "--pass-spp", pass_spp,
          "--seed", "9", "--method", method, "-o", out.string()};
}

std::string host_name() {
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  return name;
}

// The pid of the process whose environment holds `marker` (mpirun puts OMPI_COMM_WORLD_RANK
// there) and whose command line holds `text`; -1 when there is none.
pid_t find_process(const std::string& marker, const std::string& text) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string env = read_all(entry.path() / "environ"), cmdline = read_all(entry.path() / "cmdline");
    for (auto* s : {&env, &cmdline}) std::replace(s->begin(), s->end(), '\0', '\n');
    if (("\n" + env).find("\n" + marker + "\n") != std::string::npos && cmdline.find(text) != std::string::npos)
      return static_cast<pid_t>(std::stoi(name));
  }
  return -1;
}

}  // namespace

class MpiRender : public ::testing::TestWithParam<const char*> {};

TEST_P(MpiRender, TwoRanksGiveTheSingleProcessImageBitForBit) {
  if (const auto why = skip_reason(); !why.empty()) GTEST_SKIP() << why;
  TempDir dir("cohort-mpi-");
  // auto probes where its screen is at most an eighth of the render (set for the test; a CPU's own
  // rule is a 256th): 7 spp with a one-sample pool
  const bool probing = std::string(GetParam()) == "auto";
  if (probing) setenv("COHORT_AUTO_PROBE_SHARE", "8", 1);
  const std::string spp = probing ? "56" : "32";
  auto one = render_args(dir.path / "one", GetParam(), spp);
  one.insert(one.end(), {"--wavefront-size", "4096"});
  ASSERT_EQ(wait_exit(spawn(COHORT_BINARY, one)).value_or(-1), 0);
  auto args = render_args(dir.path / "two", GetParam(), spp);
  args.insert(args.end(), {"--wavefront-size", "4096", "--stats", (dir.path / "two.json").string()});
  const std::string log = (dir.path / "mpirun.log").string();
  ASSERT_EQ(wait_exit(spawn("mpirun", mpirun_args(args), log), std::chrono::seconds(300)).value_or(-1), 0)
      << read_all(log);
  EXPECT_EQ(read_all(dir.path / "one.exr"), read_all(dir.path / "two.exr"));

  const auto stats = nlohmann::json::parse(read_all(dir.path / "two.json"));
  ASSERT_EQ(stats["ranks"].size(), 2u);
  std::uint64_t passes = 0;
  for (const auto& rank : stats["ranks"]) {
    EXPECT_GT(rank["load_seconds"].get<double>(), 0);
    EXPECT_TRUE(rank.contains("build_seconds"));
    EXPECT_GT(rank["render_seconds"].get<double>(), 0);
    for (const auto& d : rank["devices"]) passes += d["passes"].get<std::uint64_t>();
  }
  EXPECT_EQ(passes, std::stoull(spp)) << "every pass rendered once, by one rank";
  if (std::string(GetParam()) == "auto") {
    // it probed (the reason is the probe's pick, or the default kept within the probe's noise)
    EXPECT_EQ(stats["auto"]["reason"].get<std::string>().find("too short"), std::string::npos) << stats["auto"];
  }
  for (const auto& rank : stats["ranks"])
    EXPECT_GT(rank["devices"][0]["passes"].get<int>(), 0) << "both ranks take passes";
  EXPECT_FALSE(fs::exists(dir.path / "two.exr.tmp"));
  if (probing) unsetenv("COHORT_AUTO_PROBE_SHARE");
}

INSTANTIATE_TEST_SUITE_P(Methods, MpiRender, ::testing::Values("naive", "pth", "auto"));

// --target-error: rank 0 sends each adaptive pass's pixel list with it; the image is the same.
TEST(MpiAdaptive, TwoRanksGiveTheSingleProcessImageBitForBit) {
  if (const auto why = skip_reason(); !why.empty()) GTEST_SKIP() << why;
  TempDir dir("cohort-mpi-");
  const auto adaptive = [&](const std::string& name) {
    // enough passes that the second rank, still loading the scene while the first renders, gets some
    auto args = render_args(dir.path / name, "naive", "256", "2");
    args.insert(args.end(), {"--fov", "58", "--target-error", "0.02", "--stats", (dir.path / (name + ".json")).string()});
    return args;
  };
  ASSERT_EQ(wait_exit(spawn(COHORT_BINARY, adaptive("one"))).value_or(-1), 0);
  const std::string log = (dir.path / "mpirun.log").string();
  ASSERT_EQ(wait_exit(spawn("mpirun", mpirun_args(adaptive("two")), log), std::chrono::seconds(300)).value_or(-1), 0)
      << read_all(log);
  EXPECT_EQ(read_all(dir.path / "one.exr"), read_all(dir.path / "two.exr"));
  const auto stats = nlohmann::json::parse(read_all(dir.path / "two.json"));
  EXPECT_GT(stats["adaptive"]["tiles_stopped_early"].get<int>(), 0) << "some tiles stopped: lists were sent";
  for (const auto& rank : stats["ranks"])
    EXPECT_GT(rank["devices"][0]["passes"].get<int>(), 0) << "both ranks take passes";
}

TEST(MpiFailure, AKilledRankEndsTheJobAndTheResumedJobGivesTheSameImage) {
  if (const auto why = skip_reason(); !why.empty()) GTEST_SKIP() << why;
  TempDir dir("cohort-mpi-");
  ASSERT_EQ(wait_exit(spawn(COHORT_BINARY, render_args(dir.path / "one", "naive", "512", "8"))).value_or(-1), 0);

  auto args = render_args(dir.path / "job", "naive", "512", "8");
  args.insert(args.end(), {"--checkpoint", "0.05"});
  const std::string log = (dir.path / "killed.log").string();
  const pid_t mpirun = spawn("mpirun", mpirun_args(args), log);
  ASSERT_TRUE(wait_for_file(dir.path / "job.checkpoint")) << read_all(log);
  const pid_t rank1 = find_process("OMPI_COMM_WORLD_RANK=1", (dir.path / "job").string());
  ASSERT_GT(rank1, 0) << "rank 1 not found";
  kill(rank1, SIGKILL);
  const auto code = wait_exit(mpirun, std::chrono::seconds(120));
  ASSERT_TRUE(code.has_value()) << "the job hangs after a rank died";
  if (*code == 0) GTEST_SKIP() << "the job finished before the kill arrived";
  const std::string output = read_all(log);
  EXPECT_NE(output.find("rank 1"), std::string::npos) << output;
  EXPECT_NE(output.find(host_name()), std::string::npos) << output;

  auto resume = args;
  resume.push_back("--resume");
  const std::string resumed_log = (dir.path / "resumed.log").string();
  ASSERT_EQ(wait_exit(spawn("mpirun", mpirun_args(resume), resumed_log), std::chrono::seconds(300)).value_or(-1), 0)
      << read_all(resumed_log);
  EXPECT_NE(read_all(resumed_log).find("resuming"), std::string::npos);
  EXPECT_EQ(read_all(dir.path / "job.exr"), read_all(dir.path / "one.exr"));
}

TEST(MpiFailure, ARankThatFailsNamesItselfAndItsHost) {
  if (const auto why = skip_reason(); !why.empty()) GTEST_SKIP() << why;
  TempDir dir("cohort-mpi-");
  // rank 1 sees no OpenCL platform: it fails while rank 0 waits for it
  std::vector<std::string> a = {"--oversubscribe"};
  if (geteuid() == 0) a.push_back("--allow-run-as-root");
  const auto cohort = render_args(dir.path / "img", "naive", "4");
  a.insert(a.end(), {"-np", "1", COHORT_BINARY});
  a.insert(a.end(), cohort.begin(), cohort.end());
  a.insert(a.end(), {":", "-np", "1", "-x", "OCL_ICD_VENDORS=/nonexistent", COHORT_BINARY});
  a.insert(a.end(), cohort.begin(), cohort.end());
  const std::string log = (dir.path / "failed.log").string();
  const auto code = wait_exit(spawn("mpirun", a, log), std::chrono::seconds(120));
  ASSERT_TRUE(code.has_value()) << "the job hangs after a rank failed";
  EXPECT_NE(*code, 0);
  const std::string output = read_all(log);
  EXPECT_NE(output.find("rank 1 of 2 on " + host_name()), std::string::npos) << output;
  EXPECT_NE(output.find("no OpenCL device"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(dir.path / "img.exr")) << "no output from a failed job";
}
