// Runs the cohort binary as a user would and checks exit codes, messages and outputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "cli/cli_helpers.h"
#include "runtime/cl/devices.h"

namespace fs = std::filesystem;
using cohort_test::CommandResult;
using cohort_test::run;
using cohort_test::TempDir;

namespace {

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

TEST(Cli, BackendCudaWithoutAGpuIsExitTwoSayingWhy) {
  EXPECT_EQ(run("render " + scene("cornell-box.gltf") + " --backend metal").code, 2);
  TempDir dir;
  const CommandResult r =
      run("render " + scene("cornell-box.gltf") + " --backend cuda --res 8x8 --spp 1 -o " + (dir.path / "box").string());
  if (r.code == 0) GTEST_SKIP() << "this machine has a CUDA GPU: it rendered";
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--backend cuda"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path / "box.exr"));
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

TEST(Cli, SortingMethodStatsNameTheCodeItsBitsAndTheFirstSortedBounce) {
  TempDir dir;
  const CommandResult r = run("render " + scene("cornell-box.gltf") + " --res 16x16 --spp 1 --method hash --code two-point"
                              " --sort-from-bounce 3 -o " + (dir.path / "box").string() + " --stats " +
                              (dir.path / "stats.json").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = nlohmann::json::parse(std::ifstream(dir.path / "stats.json"));
  EXPECT_EQ(j["coherence"]["code"], "two-point");
  EXPECT_EQ(j["coherence"]["key_bits"], 30);
  EXPECT_EQ(j["coherence"]["sort_from_bounce"], 3);
  EXPECT_EQ(run("render " + scene("cornell-box.gltf") + " --method hash --sort-from-bounce 0").code, 2);
  const CommandResult bad = run("render " + scene("cornell-box.gltf") + " --method hash --code end:11 -o " +
                                (dir.path / "bad").string());
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("end takes at most 10 bits"), std::string::npos) << bad.output;
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
  // by default the tree a render builds: the 4-wide BVH
  for (const char* word : {"triangles:", "materials:", "lights:", "bounds:", "4-wide BVH: depth", "memory:"})
    EXPECT_NE(r.output.find(word), std::string::npos) << word << "\n" << r.output;
  EXPECT_EQ(r.output.find("kd-tree"), std::string::npos) << r.output;
  const CommandResult deep = run("info " + scene("cornell-box.gltf") + " --tree deep");
  ASSERT_EQ(deep.code, 0) << deep.output;
  EXPECT_NE(deep.output.find("kd-tree (deep):"), std::string::npos) << deep.output;
  const CommandResult compact = run("info " + scene("cornell-box.gltf") + " --tree compact");
  ASSERT_EQ(compact.code, 0) << compact.output;
  EXPECT_NE(compact.output.find("kd-tree (compact):"), std::string::npos) << compact.output;
  const CommandResult bvh = run("info " + scene("cornell-box.gltf") + " --tree bvh4");
  ASSERT_EQ(bvh.code, 0) << bvh.output;
  EXPECT_NE(bvh.output.find("4-wide BVH: depth"), std::string::npos) << bvh.output;
  EXPECT_EQ(run("info " + scene("cornell-box.gltf") + " --tree sparse").code, 2);
}

// --tree all: every layout the renderer can trace, each with its device bytes per triangle.
TEST(Cli, InfoAllListsEachLayoutsMemory) {
  const CommandResult r = run("info " + scene("cornell-box.gltf") + " --tree all");
  ASSERT_EQ(r.code, 0) << r.output;
  std::size_t at = 0;
  for (const char* layout :
       {"4-wide BVH: depth", "compressed 8-wide BVH: depth", "8-wide BVH (float planes): depth", "kd-tree (deep):",
        "kd-tree (compact):"}) {
    at = r.output.find(layout, at);
    ASSERT_NE(at, std::string::npos) << layout << "\n" << r.output;
    const std::size_t memory = r.output.find("device memory: ", at);
    ASSERT_NE(memory, std::string::npos) << r.output;
    EXPECT_NE(r.output.substr(memory, r.output.find('\n', memory) - memory).find("bytes per triangle"),
              std::string::npos) << r.output;
  }
}

// --tree picks what rays are traced through (auto: the 4-wide BVH unless the method walks the
// KD-tree); the closest hit does not depend on it, so every choice writes the same image, bit for
// bit.
TEST(Cli, EveryTreeRendersTheSameImage) {
  TempDir dir;
  std::string images[6];
  nlohmann::json stats[6];
  const char* trees[6] = {"deep", "compact", "auto", "bvh4", "bvh8", "bvh8f"};
  for (int k = 0; k < 6; ++k) {
    const auto out = dir.path / trees[k];
    const CommandResult r = run("render " + scene("cornell-box.gltf") + " --res 40x32 --spp 8 --method sc --tree " +
                                trees[k] + " -o " + out.string() + " --stats " + (dir.path / "s.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream exr(out.string() + ".exr", std::ios::binary);
    images[k].assign(std::istreambuf_iterator<char>(exr), {});
    stats[k] = nlohmann::json::parse(std::ifstream(dir.path / "s.json"));
  }
  EXPECT_EQ(stats[0]["kdtree"]["kind"], "deep");
  EXPECT_EQ(stats[1]["kdtree"]["kind"], "compact");
  EXPECT_LT(stats[1]["kdtree"]["nodes"].get<int>(), stats[0]["kdtree"]["nodes"].get<int>());
  // auto with sc: the 8-wide BVH with float planes on a CPU, the 4-wide one on a GPU
  EXPECT_EQ(stats[2]["kdtree"]["kind"], cohort::select_device("").is_gpu ? "bvh4" : "bvh8f") << "auto with sc";
  EXPECT_EQ(stats[3]["kdtree"]["kind"], "bvh4");
  EXPECT_GT(stats[3]["kdtree"]["bvh4"]["nodes"].get<int>(), 0);
  EXPECT_EQ(stats[3]["kdtree"]["nodes"].get<int>(), 1) << "with the BVH the KD-tree only keeps the triangles";
  ASSERT_FALSE(images[0].empty());
  EXPECT_TRUE(images[0] == images[1]) << "deep and compact trees rendered different images";
  EXPECT_TRUE(images[0] == images[2]) << "auto's tree rendered a different image";
  EXPECT_TRUE(images[0] == images[3]) << "the 4-wide BVH rendered a different image";
  EXPECT_EQ(stats[4]["kdtree"]["kind"], "bvh8");
  EXPECT_GT(stats[4]["kdtree"]["bvh8"]["nodes"].get<int>(), 0);
  EXPECT_TRUE(images[0] == images[4]) << "the 8-wide BVH rendered a different image";
  EXPECT_EQ(stats[5]["kdtree"]["kind"], "bvh8f");
  EXPECT_GT(stats[5]["kdtree"]["bvh8f"]["nodes"].get<int>(), 0);
  EXPECT_TRUE(images[0] == images[5]) << "the 8-wide BVH with float planes rendered a different image";
  // hash and pth do not walk the 8-wide BVHs: an error naming the tree, no image
  for (const char* tree : {"bvh8", "bvh8f"}) {
    for (const char* method : {"pth", "hash"}) {
      const CommandResult r = run("render " + scene("cornell-box.gltf") + " --res 8x8 --spp 1 --method " + method +
                                  " --tree " + tree + " -o " + (dir.path / "x8").string());
      EXPECT_EQ(r.code, 2) << method << " on " << tree << ": " << r.output;
      EXPECT_NE(r.output.find(std::string("--tree ") + tree + ":"), std::string::npos) << r.output;
      EXPECT_FALSE(fs::exists(dir.path / "x8.exr"));
    }
  }
  // pth and hash walk the top of whichever tree is built: the BVH by default, the KD-tree when asked
  for (const char* method : {"pth", "hash"}) {
    for (const char* tree : {"auto", "deep"}) {
      const auto out = dir.path / (std::string(method) + "-" + tree);
      const CommandResult r = run("render " + scene("cornell-box.gltf") + " --res 40x32 --spp 8 --method " + method +
                                  " --tree " + tree + " -o " + out.string() + " --stats " + (dir.path / "s.json").string());
      ASSERT_EQ(r.code, 0) << r.output;
      EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir.path / "s.json"))["kdtree"]["kind"] == "bvh4",
                std::string(tree) == "auto")
          << method << " on " << tree;
      std::ifstream exr(out.string() + ".exr", std::ios::binary);
      EXPECT_TRUE(images[0] == std::string(std::istreambuf_iterator<char>(exr), {}))
          << method << " on " << tree << " rendered another image";
    }
  }
  // speculation is the KD-tree walk's: with the BVH asked for, an error before rendering; auto builds
  // the KD-tree for it
  const CommandResult speculative = run("render " + scene("cornell-box.gltf") +
                                        " --res 8x8 --spp 1 --method pth --speculative --tree bvh4 -o " +
                                        (dir.path / "x").string());
  EXPECT_EQ(speculative.code, 2) << speculative.output;
  EXPECT_NE(speculative.output.find("KD-tree"), std::string::npos) << speculative.output;
  EXPECT_FALSE(fs::exists(dir.path / "x.exr"));
  const CommandResult speculative_auto =
      run("render " + scene("cornell-box.gltf") + " --res 40x32 --spp 8 --method pth --speculative -o " +
          (dir.path / "spec").string() + " --stats " + (dir.path / "s.json").string());
  ASSERT_EQ(speculative_auto.code, 0) << speculative_auto.output;
  EXPECT_NE(nlohmann::json::parse(std::ifstream(dir.path / "s.json"))["kdtree"]["kind"], "bvh4");
  std::ifstream spec_exr((dir.path / "spec.exr").string(), std::ios::binary);
  EXPECT_TRUE(images[0] == std::string(std::istreambuf_iterator<char>(spec_exr), {})) << "speculative pth";
  EXPECT_EQ(run("render " + scene("cornell-box.gltf") + " --tree sparse -o " + (dir.path / "x").string()).code, 2);
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
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("needs at least 0.27 MiB"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the limit is 0.01 MiB"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path / "x.exr"));
  // the BVH cannot trade depth for bytes: asked for by name, it fails naming itself and the KD-trees
  const CommandResult bvh = run("render " + scene("furnace-sphere.gltf") + " --res 8x8 --spp 1 --tree bvh4 "
                                "--memory-limit 0.01 -o " + (dir.path / "x").string());
  EXPECT_EQ(bvh.code, 2) << bvh.output;
  EXPECT_NE(bvh.output.find("4-wide BVH"), std::string::npos) << bvh.output;
  EXPECT_NE(bvh.output.find("--tree deep or compact"), std::string::npos) << bvh.output;
  EXPECT_FALSE(fs::exists(dir.path / "x.exr"));
}

TEST(Cli, MemoryLimitAndTreeBudgetMakeTheTreeShallowerToFit) {
  // The furnace sphere needs 0.5 MiB with the deep tree (0.27 MiB with a single leaf).
  TempDir dir;
  const auto stats = dir.path / "s.json";
  const CommandResult full = run("render " + scene("furnace-sphere.gltf") + " --tree deep --res 8x8 --spp 1 -o " +
                                 (dir.path / "a").string() + " --stats " + stats.string());
  ASSERT_EQ(full.code, 0) << full.output;
  const auto full_stats = nlohmann::json::parse(std::ifstream(stats));
  for (const char* limit : {"--memory-limit 0.35", "--tree-budget 0.2"}) {
    SCOPED_TRACE(limit);
    const CommandResult r = run("render " + scene("furnace-sphere.gltf") + " --tree deep --res 8x8 --spp 1 " + limit +
                                " -o " + (dir.path / "b").string() + " --stats " + stats.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const auto s = nlohmann::json::parse(std::ifstream(stats));
    EXPECT_LT(s["kdtree"]["nodes"].get<int>(), full_stats["kdtree"]["nodes"].get<int>());
    EXPECT_LE(s["device_memory"]["total"].get<double>(), 0.35 * 1048576.0);
    EXPECT_LE(s["kdtree"]["bytes"].get<double>(), 0.35 * 1048576.0);
    EXPECT_EQ(s["device_memory"]["triangles"], full_stats["device_memory"]["triangles"]);
  }
}

// Under --memory-limit, --tree auto's BVH falls back to the KD-tree where it does not fit: on a CPU
// the 8-wide BVH with float planes (0.67 MiB for the furnace sphere; the 4-wide one takes 0.88) to
// the CPU's compact KD-tree (0.40 MiB). Where it fits, it stays.
TEST(Cli, AutoFallsBackToTheKdTreeWhereItsBvhDoesNotFit) {
  TempDir dir;
  for (const auto& [limit, kind] : {std::pair{"0.6", "compact"}, std::pair{"0.7", "bvh8f"}}) {
    const auto stats = dir.path / "s.json";
    const CommandResult r = run("render " + scene("furnace-sphere.gltf") + " --method naive --res 8x8 --spp 1 " +
                                "--memory-limit " + limit + " -o " + (dir.path / "m").string() + " --stats " +
                                stats.string());
    ASSERT_EQ(r.code, 0) << r.output;
    const auto s = nlohmann::json::parse(std::ifstream(stats));
    EXPECT_EQ(s["kdtree"]["kind"], kind) << limit;
    EXPECT_LE(s["device_memory"]["total"].get<double>(), std::stod(limit) * 1048576.0);
  }
}

// A scene beyond the compressed 8-wide BVH's bound (1e19 from the origin): --tree bvh8 refuses it
// with the file's name and exit 2, writing nothing; the 4-wide BVH renders it; info --tree all says
// why the compressed BVH is missing and lists the others.
TEST(Cli, TheCompressedBvhRefusesASceneBeyondItsBound) {
  TempDir dir;
  const fs::path obj = dir.path / "far.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 3e20 0 0\nv 3e20 1 0\nv 3e20 0 1\nf 1 2 3\nf 4 5 6\n";
  const CommandResult refused = run("render " + obj.string() + " --tree bvh8 --res 8x8 --spp 1 -o " +
                                    (dir.path / "a").string());
  EXPECT_EQ(refused.code, 2) << refused.output;
  EXPECT_NE(refused.output.find(obj.string() + ": the 8-wide BVH (--tree bvh8) takes vertices within"),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(dir.path / "a.exr"));
  const CommandResult wide4 = run("render " + obj.string() + " --tree bvh4 --res 8x8 --spp 1 -o " +
                                  (dir.path / "b").string());
  EXPECT_EQ(wide4.code, 0) << wide4.output;
  const CommandResult info = run("info " + obj.string() + " --tree all");
  EXPECT_EQ(info.code, 0) << info.output;
  EXPECT_NE(info.output.find("compressed 8-wide BVH: not built: "), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("8-wide BVH (float planes): depth"), std::string::npos) << info.output;
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

// `cohort bench` at a tiny size: the JSON holds every figure the benchmark scripts and charts read.
TEST(Cli, BenchWritesEveryFigureAsJson) {
  TempDir dir;
  const fs::path json = dir.path / "bench.json";
  const CommandResult r = run("bench " + scene("cornell-box.gltf") +
                              " --res 8 --trace-res 16 --spp 1 --reps 3 --json " + json.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("pth / naive"), std::string::npos) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_FALSE(j["cohort"]["git_commit"].get<std::string>().empty());
  EXPECT_FALSE(j["cohort"]["kernel_build_options"].get<std::string>().empty());
  EXPECT_FALSE(j["device"]["name"].get<std::string>().empty());
  EXPECT_TRUE(j["device"].contains("driver"));
  EXPECT_EQ(j["device"]["backend"], "opencl");  // the default
  EXPECT_EQ(j["settings"]["reps"], 3);
  ASSERT_EQ(j["scenes"].size(), 1u);
  const auto& s = j["scenes"][0];
  EXPECT_EQ(s["triangles"], 38);
  EXPECT_GE(s["kdtree"]["build_seconds"].get<double>(), 0.0);
  ASSERT_EQ(s["views"].size(), 1u);
  const auto& v = s["views"][0];
  EXPECT_EQ(v["view"], "exterior");
  EXPECT_EQ(v["primary"]["rays"], 256);
  EXPECT_GT(v["primary"]["hits"].get<int>(), 0);
  EXPECT_EQ(v["diffuse"]["rays"], v["primary"]["hits"]);  // one diffuse ray per primary hit
  EXPECT_EQ(v["primary"]["mrays_per_second"]["runs"].size(), 3u);
  EXPECT_GT(v["primary"]["mrays_per_second"]["median"].get<double>(), 0.0);
  for (const char* m : {"naive", "wavefront", "sc", "rg", "sc+rg", "hash", "pth"}) {
    const auto& pt = v["path_tracing"][m];
    EXPECT_GT(pt["rays"].get<std::uint64_t>(), 0u) << m;
    EXPECT_GT(pt["mrays_per_second"]["median"].get<double>(), 0.0) << m;
    EXPECT_GT(pt["msamples_per_second"]["best"].get<double>(), 0.0) << m;
    EXPECT_GT(pt["msamples_per_cpu_second"]["best"].get<double>(), 0.0) << m;
    EXPECT_TRUE(pt.contains("simd_efficiency")) << m;
    EXPECT_FALSE(pt["breakdown_seconds"].empty()) << m;
  }
  // every method traces the same paths: the same ray count
  EXPECT_EQ(v["path_tracing"]["pth"]["rays"], v["path_tracing"]["naive"]["rays"]);
  const auto& pth = v["path_tracing"]["pth"]["breakdown_seconds"];
  for (const char* stage : {"pth walk", "sort", "resume traversal", "shading"}) EXPECT_TRUE(pth.contains(stage)) << stage;
}

TEST(Cli, BenchInteriorViewAndTraversalOnly) {
  TempDir dir;
  const fs::path json = dir.path / "bench.json";
  const CommandResult r = run("bench " + scene("cornell-box.gltf") + " --view exterior,interior --methods none " +
                              "--trace-res 8 --backend opencl --json " + json.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["device"]["backend"], "opencl");
  const auto& views = j["scenes"][0]["views"];
  ASSERT_EQ(views.size(), 2u);
  EXPECT_EQ(views[1]["view"], "interior");
  EXPECT_EQ(views[1]["camera"]["vfov_degrees"], 60.0);
  EXPECT_TRUE(views[1]["path_tracing"].empty());
}

// bench opens its device as render does: --backend cuda without a GPU is an error saying why,
// before any scene is loaded or file written, not an unknown option.
TEST(Cli, BenchBackendCudaWithoutAGpuIsExitTwoSayingWhy) {
  EXPECT_EQ(run("bench --backend metal --methods none --trace-res 8").code, 2);
  TempDir dir;
  const fs::path json = dir.path / "bench.json";
  const CommandResult r =
      run("bench " + scene("cornell-box.gltf") + " --backend cuda --methods none --trace-res 8 --json " + json.string());
  if (r.code == 0) GTEST_SKIP() << "this machine has a CUDA GPU: it measured";
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--backend cuda"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(json));
}

TEST(Cli, BenchRejectsBadOptionsWithExitTwo) {
  EXPECT_EQ(run("bench --methods naive,nonsense --trace-res 8").code, 2);
  EXPECT_EQ(run("bench --reps 1").code, 2);  // the protocol asks for at least 3
  EXPECT_EQ(run("bench --view sideways").code, 2);
  const CommandResult r = run("bench /nonexistent/mesh.ply --methods none");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("mesh.ply"), std::string::npos) << r.output;
}

TEST(Cli, ExportWritesSubdividedTriangles) {
  TempDir dir;
  const fs::path ply = dir.path / "box.ply";
  const CommandResult r = run("export " + scene("cornell-box.gltf") + " -o " + ply.string() + " --subdivide 1");
  ASSERT_EQ(r.code, 0) << r.output;
  const CommandResult info = run("info " + ply.string());
  ASSERT_EQ(info.code, 0) << info.output;
  EXPECT_NE(info.output.find("triangles: 152 "), std::string::npos) << info.output;  // 38 x 4
}
