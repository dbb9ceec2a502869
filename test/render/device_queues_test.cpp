// The wavefront loop keeps queue lengths and per-bounce figures on the device and reads them only
// every few bounces (runtime/render/stages/wavefront_loop.cpp): the figures it reports must still
// add up, and the reads must stay rare.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "render_fixture.h"

using namespace cohort;
using namespace cohort::test;

namespace {

RenderResult render_cornell(const char* method, std::uint32_t wavefront_size) {
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.spp = 4;
  s.seed = 5;
  s.rr_depth = 2;
  s.method = method;
  s.wavefront_size = wavefront_size;
  return render_scene(shipped_scene("cornell-box.gltf"), s);
}

class DeviceQueues : public ::testing::TestWithParam<const char*> {};

TEST_P(DeviceQueues, BounceFiguresAddUpAndReadsAreRare) {
  // a pool of 500 slots for 3072 paths: many refills, and bounces that run after the last path ended
  const RenderResult r = render_cornell(GetParam(), 500);
  ASSERT_FALSE(r.iterations.empty());
  std::uint64_t rays = 0, bounces_traced = 0;
  for (const IterationStats& it : r.iterations) {
    EXPECT_GT(it.live_paths, 0u) << "a bounce that traced nothing is reported";
    rays += it.live_paths + it.shadow_rays;
  }
  EXPECT_EQ(rays, r.rays) << "the per-bounce rows disagree with the render's ray count";
  // every path traces its camera ray in some bounce: the first bounces hold at least the pixels
  EXPECT_GE(r.iterations.front().live_paths, 500u);
  ASSERT_FALSE(r.pass_host_reads.empty());
  ASSERT_EQ(r.pass_host_reads.size(), r.pass_sort_launches.size());
  for (const IterationStats& it : r.iterations) bounces_traced += it.live_paths > 0;
  const std::uint32_t most_reads = *std::max_element(r.pass_host_reads.begin(), r.pass_host_reads.end());
  EXPECT_GE(most_reads, 1u);
  // reading every bounce would take as many reads as the longest pass has bounces
  EXPECT_LT(most_reads, bounces_traced) << "the loop reads the device about every bounce";
  const std::uint32_t sort_commands = std::accumulate(r.pass_sort_launches.begin(), r.pass_sort_launches.end(), 0u);
  const std::string method = GetParam();
  if (method == "pth" || method == "hash")
    EXPECT_GT(sort_commands, 0u);
  else
    EXPECT_EQ(sort_commands, 0u);
}

INSTANTIATE_TEST_SUITE_P(Methods, DeviceQueues, ::testing::Values("wavefront", "sc", "rg", "sc+rg", "hash", "pth"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '+', '_');
                           return name;
                         });

// Paths of at most max_depth segments in a pool that holds the whole pass: all of them have ended
// after max_depth bounces, so one read per pass ends it (the white-sky benchmark's case).
TEST(DeviceQueuesBoundedDepth, OneReadPerPassWhenEveryPathFitsAndDepthIsBounded) {
  for (const char* method : {"sc", "pth"}) {
    RenderSettings s;
    s.width = 32;
    s.height = 24;
    s.spp = 2;
    s.pass_samples = 1;
    s.max_depth = 5;
    s.russian_roulette = false;
    s.method = method;
    s.wavefront_size = 32 * 24;  // one pass's paths exactly
    const RenderResult r = render_scene(shipped_scene("cornell-box.gltf"), s);
    ASSERT_EQ(r.pass_host_reads.size(), 2u) << method;
    for (std::uint32_t reads : r.pass_host_reads) EXPECT_EQ(reads, 1u) << method;
    EXPECT_LE(r.iterations.size(), 5u) << method << ": a path traced more segments than max_depth";
  }
}

}  // namespace
