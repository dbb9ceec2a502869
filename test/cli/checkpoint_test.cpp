// A render interrupted by SIGINT and resumed equals the uninterrupted render bit for bit.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>

extern char** environ;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("cohort-ckpt-" + std::to_string(std::random_device{}()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

pid_t spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(COHORT_BINARY));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, COHORT_BINARY, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> render_args(const fs::path& out, const char* method) {
  return {"render", std::string(COHORT_SOURCE_DIR) + "/scenes/cornell-box.gltf", "--res", "64x64", "--spp", "256",
          "--seed", "9", "--method", method, "-o", out.string()};
}

}  // namespace

class Checkpoint : public ::testing::TestWithParam<const char*> {};

TEST_P(Checkpoint, InterruptedAndResumedEqualsUninterrupted) {
  TempDir dir;
  ASSERT_EQ(wait_exit(spawn(render_args(dir.path / "full", GetParam()))), 0);

  auto args = render_args(dir.path / "part", GetParam());
  args.insert(args.end(), {"--checkpoint", "0.05"});
  const pid_t pid = spawn(args);
  // interrupt once the first checkpoint proves the render loop is running
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(dir.path / "part.checkpoint") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGINT);
  const int code = wait_exit(pid);
  if (code == 0) GTEST_SKIP() << "the render finished before the interrupt arrived";
  EXPECT_EQ(code, 128 + SIGINT);
  EXPECT_TRUE(fs::exists(dir.path / "part.exr")) << "the image so far must be written";
  EXPECT_NE(read_all(dir.path / "part.exr"), read_all(dir.path / "full.exr")) << "it stopped early";

  auto resume = render_args(dir.path / "part", GetParam());
  resume.push_back("--resume");
  ASSERT_EQ(wait_exit(spawn(resume)), 0);
  EXPECT_EQ(read_all(dir.path / "part.exr"), read_all(dir.path / "full.exr"));
}

INSTANTIATE_TEST_SUITE_P(Methods, Checkpoint, ::testing::Values("naive", "sc+rg"),
                         [](const auto& info) { return std::string(info.param) == "naive" ? "naive" : "sc_rg"; });

TEST(CheckpointRejects, OtherSettingsOrDamagedFiles) {
  TempDir dir;
  auto args = render_args(dir.path / "img", "naive");
  args[5] = "4";  // --spp 4
  args.push_back("--checkpoint");
  args.push_back("100");
  ASSERT_EQ(wait_exit(spawn(args)), 0);
  ASSERT_TRUE(fs::exists(dir.path / "img.checkpoint"));

  auto other_seed = render_args(dir.path / "img", "naive");
  other_seed[7] = "10";  // --seed 10
  other_seed.push_back("--resume");
  EXPECT_EQ(wait_exit(spawn(other_seed)), 2);

  std::ofstream(dir.path / "img.checkpoint", std::ios::binary | std::ios::app) << "junk";
  auto damaged = render_args(dir.path / "img", "naive");
  damaged.push_back("--resume");
  EXPECT_EQ(wait_exit(spawn(damaged)), 2);
}
