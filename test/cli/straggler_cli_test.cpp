// --stats' straggler figures and `cohort replay`, run as a user would.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/cli_helpers.h"

using cohort_test::CommandResult;
using cohort_test::run;
using cohort_test::TempDir;

namespace {

nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace

// Through the BVH (--tree auto) and through the KD-tree: replay rebuilds the render's structure.
class StragglerStats : public ::testing::TestWithParam<const char*> {};

TEST_P(StragglerStats, ReportPassTimesAndTheMostNodesOneRayVisited) {
  TempDir dir;
  const std::string box = cohort_test::shipped_scene("cornell-box.gltf");
  const auto stats = dir.path / "s.json";
  const CommandResult r = run("render " + box + " --res 24x16 --spp 4 --pass-spp 1 --method wavefront --stragglers 3 " +
                              "--tree " + GetParam() + " --stats " + stats.string() + " -o " + (dir.path / "img").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = read_json(stats);
  EXPECT_EQ(j["passes"].get<int>(), 4);
  const double median = j["pass_seconds"]["median"], most = j["pass_seconds"]["max"];
  EXPECT_GT(median, 0.0);
  EXPECT_GE(most, median);
  const auto& worst = j["stragglers"]["worst"];
  ASSERT_EQ(worst.size(), 3u);
  EXPECT_EQ(j["stragglers"]["per_pass"].size(), 4u);
  // the worst ray is the most nodes any extension ray visited; shadow rays may visit more
  EXPECT_GE(j["max_nodes_per_ray"].get<std::uint32_t>(), worst[0]["nodes"].get<std::uint32_t>());
  EXPECT_GE(worst[0]["nodes"].get<std::uint32_t>(), worst[2]["nodes"].get<std::uint32_t>());
  std::uint32_t pass_max = 0;
  for (const auto& p : j["stragglers"]["per_pass"]) pass_max = std::max(pass_max, p["max"].get<std::uint32_t>());
  EXPECT_EQ(pass_max, worst[0]["nodes"].get<std::uint32_t>());

  // the same rays on the host visit the same number of nodes
  const CommandResult replay = run("replay " + box + " " + stats.string());
  ASSERT_EQ(replay.code, 0) << replay.output;
  int lines = 0;
  std::istringstream out(replay.output);
  for (std::string text; std::getline(out, text);) {
    unsigned device = 0, host = 0;
    if (std::sscanf(text.c_str(), "device %u nodes, host %u nodes", &device, &host) != 2) continue;
    ++lines;
    EXPECT_EQ(device, host) << text;
  }
  EXPECT_EQ(lines, 3) << replay.output;
}

INSTANTIATE_TEST_SUITE_P(Trees, StragglerStats, ::testing::Values("auto", "deep"));

TEST(Stragglers, MisuseIsExitTwoSayingWhy) {
  TempDir dir;
  const std::string box = cohort_test::shipped_scene("cornell-box.gltf");
  const CommandResult naive = run("render " + box + " --res 8x8 --spp 1 --stragglers 2 --stats " +
                                  (dir.path / "s.json").string() + " -o " + (dir.path / "a").string());
  EXPECT_EQ(naive.code, 2) << naive.output;
  EXPECT_NE(naive.output.find("--method wavefront"), std::string::npos) << naive.output;
  const CommandResult no_stats =
      run("render " + box + " --res 8x8 --spp 1 --method sc --stragglers 2 -o " + (dir.path / "b").string());
  EXPECT_EQ(no_stats.code, 2) << no_stats.output;
  std::ofstream(dir.path / "bad.json") << "{\"stragglers\": {\"worst\": [{\"nodes\": 1, \"org\": [\"0x1p+0\", \"zero\", "
                                          "\"0\"], \"dir\": [\"1\", \"0\", \"0\"], \"tmin\": \"0\", \"tmax\": \"inf\"}]}}";
  const CommandResult bad = run("replay " + box + " " + (dir.path / "bad.json").string());
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.json"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("zero"), std::string::npos) << bad.output;
}
