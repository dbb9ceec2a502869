// A render interrupted by SIGINT and resumed equals the uninterrupted render bit for bit.
#include <gtest/gtest.h>

#include <signal.h>

#include "cli/cli_helpers.h"

using namespace cohort_test;

namespace {

int run_cohort(const std::vector<std::string>& args) { return wait_exit(spawn(COHORT_BINARY, args)).value_or(-1); }

std::vector<std::string> render_args(const fs::path& out, const char* method) {
  return {"render", std::string(COHORT_SOURCE_DIR) + "/scenes/cornell-box.gltf", "--res", "64x64", "--spp", "256",
          "--seed", "9", "--method", method, "-o", out.string(),
          "--pass-spp", "4"};  // 64 passes: an interrupt lands between two
}

}  // namespace

class Checkpoint : public ::testing::TestWithParam<const char*> {};

TEST_P(Checkpoint, InterruptedAndResumedEqualsUninterrupted) {
  TempDir dir("cohort-ckpt-");
  ASSERT_EQ(run_cohort(render_args(dir.path / "full", GetParam())), 0);

  auto args = render_args(dir.path / "part", GetParam());
  args.insert(args.end(), {"--checkpoint", "0.05"});
  const pid_t pid = spawn(COHORT_BINARY, args);
  // interrupt once the first checkpoint proves the render loop is running
  wait_for_file(dir.path / "part.checkpoint");
  kill(pid, SIGINT);
  const int code = wait_exit(pid).value_or(-1);
  if (code == 0) GTEST_SKIP() << "the render finished before the interrupt arrived";
  EXPECT_EQ(code, 128 + SIGINT);
  EXPECT_TRUE(fs::exists(dir.path / "part.exr")) << "the image so far must be written";
  EXPECT_NE(read_all(dir.path / "part.exr"), read_all(dir.path / "full.exr")) << "it stopped early";

  auto resume = render_args(dir.path / "part", GetParam());
  resume.push_back("--resume");
  ASSERT_EQ(run_cohort(resume), 0);
  EXPECT_EQ(read_all(dir.path / "part.exr"), read_all(dir.path / "full.exr"));
}

INSTANTIATE_TEST_SUITE_P(Methods, Checkpoint, ::testing::Values("naive", "sc+rg"),
                         [](const auto& info) { return std::string(info.param) == "naive" ? "naive" : "sc_rg"; });

TEST(CheckpointRejects, OtherSettingsOrDamagedFiles) {
  TempDir dir("cohort-ckpt-");
  auto args = render_args(dir.path / "img", "naive");
  args[5] = "4";  // --spp 4
  args.push_back("--checkpoint");
  args.push_back("100");
  ASSERT_EQ(run_cohort(args), 0);
  ASSERT_TRUE(fs::exists(dir.path / "img.checkpoint"));

  auto other_seed = render_args(dir.path / "img", "naive");
  other_seed[7] = "10";  // --seed 10
  other_seed.push_back("--resume");
  EXPECT_EQ(run_cohort(other_seed), 2);

  std::ofstream(dir.path / "img.checkpoint", std::ios::binary | std::ios::app) << "junk";
  auto damaged = render_args(dir.path / "img", "naive");
  damaged.push_back("--resume");
  EXPECT_EQ(run_cohort(damaged), 2);
}
