// Every wavefront method traces the reference paths and adds them to the film in the same order,
// so it must give the NAIVE image bit for bit on the same device.
#include <gtest/gtest.h>

#include <cstdlib>

#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "method_tree_agreement.h"
#include "render_fixture.h"
#include "runtime/backend/device_support.h"
#include "runtime/render/pth/coherence.h"
#include "runtime/render/methods/methods.h"
#include "runtime/render/workloads.h"
#include "runtime/util/error.h"
#include "kernels/common/shading/camera.h"
#include "runtime/render/scene/camera_params.h"

using namespace cohort;
using namespace cohort::test;

namespace {

struct AgreementCase {
  const char* method;
  std::uint32_t wavefront_size;  // 0: the device default; small odd pools force many refills
  bool speculative = false;      // hash/pth: speculative resumed traversal
  const char* payload = "indirect";  // hash/pth: --sort-payload
};

class MethodAgreement : public ::testing::TestWithParam<AgreementCase> {};

// A render of the shipped box small enough to repeat for many settings.
RenderSettings small_box_settings(std::uint32_t seed) {
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.spp = 3;
  s.seed = seed;
  return s;
}

// Sets COHORT_AUTO_PROBE_SHARE for the test's scope: auto probes where its screen is at most 1/N of
// the render (a CPU's own rule, 1/256, would need thousands of samples per pixel).
struct ProbeShare {
  explicit ProbeShare(const char* n) { setenv("COHORT_AUTO_PROBE_SHARE", n, 1); }
  ~ProbeShare() { unsetenv("COHORT_AUTO_PROBE_SHARE"); }
  ProbeShare(const ProbeShare&) = delete;
  ProbeShare& operator=(const ProbeShare&) = delete;
};

// hash and pth sort on the device; a device whose work-groups do not run independently cannot
// (device_support), and render() refuses them there.
bool device_cannot_sort(const char* method) {
  const std::string m = method;
  return (m == "hash" || m == "pth") && !device_support(ClContext(select_device("")).info()).sorts;
}

void expect_bitwise_equal(const RenderResult& reference, const RenderResult& other, const char* what) {
  ASSERT_EQ(reference.image.rgb.size(), other.image.rgb.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < reference.image.rgb.size(); ++i)
    if (std::memcmp(&reference.image.rgb[i], &other.image.rgb[i], sizeof(float)) != 0) ++differing;
  EXPECT_EQ(differing, 0u) << what << ": values differ from the naive image";
  EXPECT_EQ(reference.rays, other.rays) << what << ": a different number of rays";
  EXPECT_EQ(reference.dropped_samples, other.dropped_samples);
}

TEST_P(MethodAgreement, CornellBoxBitForBit) {
  if (device_cannot_sort(GetParam().method)) GTEST_SKIP() << "this device runs no sorting method";
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.spp = 6;
  s.seed = 11;
  s.rr_depth = 2;  // paths of very different lengths: regeneration and compaction have work to do
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult reference = render_scene(path, s);
  s.method = GetParam().method;
  s.wavefront_size = GetParam().wavefront_size;
  s.speculative = GetParam().speculative;
  s.sort.sort_payload = GetParam().payload;
  const RenderResult other = render_scene(path, s);
  expect_bitwise_equal(reference, other, GetParam().method);
  if (GetParam().wavefront_size) {
    EXPECT_EQ(other.wavefront.slots, GetParam().wavefront_size);
  }
  EXPECT_FALSE(other.iterations.empty());
}

TEST_P(MethodAgreement, SharedModelUnderWhiteSkyBitForBit) {
  const std::filesystem::path model = std::filesystem::path(COHORT_SHARED_SCENES) / "bunny/bun_zipper_res3.ply";
  if (!std::filesystem::exists(model)) GTEST_SKIP() << "the external models (scenes/external.json) are missing";
  if (device_cannot_sort(GetParam().method)) GTEST_SKIP() << "this device runs no sorting method";
  PreparedScene prepared = prepare_scene(model);
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 3;
  apply_white_sky(prepared, s);
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  const DeviceScene scene = upload_scene(cl, prepared.tree, prepared.tables);
  const RenderResult reference = render(cl, cache, scene, prepared.camera, s);
  s.method = GetParam().method;
  s.wavefront_size = GetParam().wavefront_size;
  s.speculative = GetParam().speculative;
  s.sort.sort_payload = GetParam().payload;
  const RenderResult other = render(cl, cache, scene, prepared.camera, s);
  expect_bitwise_equal(reference, other, GetParam().method);
}

INSTANTIATE_TEST_SUITE_P(Methods, MethodAgreement,
                         ::testing::Values(AgreementCase{"wavefront", 0}, AgreementCase{"sc", 0},
                                           AgreementCase{"rg", 0}, AgreementCase{"sc+rg", 0},
                                           AgreementCase{"wavefront", 333}, AgreementCase{"sc", 1000},
                                           AgreementCase{"rg", 97}, AgreementCase{"sc+rg", 1},
                                           AgreementCase{"hash", 0}, AgreementCase{"pth", 0},
                                           AgreementCase{"hash", 129}, AgreementCase{"pth", 1000},
                                           AgreementCase{"pth", 0, true}, AgreementCase{"hash", 129, true},
                                           AgreementCase{"pth", 1000, true}, AgreementCase{"hash", 129, false, "gather"},
                                           AgreementCase{"pth", 1000, false, "gather"},
                                           AgreementCase{"pth", 0, true, "gather"}),
                         [](const auto& info) {
                           std::string name = info.param.method;
                           for (char& c : name)
                             if (c == '+') c = '_';
                           return name + "_pool" + std::to_string(info.param.wavefront_size) +
                                  (info.param.speculative ? "_speculative" : "") + "_" + info.param.payload;
                         });

TEST(Methods, PthWithOtherCodeLayoutsAndSubtreeDepthsStillBitForBit) {
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.spp = 4;
  s.seed = 2;
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult reference = render_scene(path, s);
  s.method = "pth";
  // --code pth:N walks N levels (capped by the tree's depth), whatever the default would be
  struct Case {
    const char* code;
    std::uint32_t levels;  // the pth width the layout asks for; 0: the default's 10
  };
  for (const Case& c : {Case{"pth:4", 4}, Case{"dir:16,pth:6,origin:4", 6}, Case{"origin-uniform:10,pth:12", 12},
                        Case{"pth:16,dir:16", 16}, Case{"paper", 10}, Case{"pth:1,origin-uniform:8,dir:4", 1}}) {
    s.sort.code = c.code;
    // the gathered copies hold every saved stack entry, up to 16
    s.sort.sort_payload = c.levels >= 12 ? "gather" : "indirect";
    const RenderResult r = render_scene(path, s);
    expect_bitwise_equal(reference, r, c.code);
    ASSERT_TRUE(r.coherence) << c.code;
    EXPECT_EQ(r.coherence->sort.code, c.code);
    EXPECT_GT(r.coherence->sort.pth_levels, 0u) << c.code;
    EXPECT_LE(r.coherence->sort.pth_levels, c.levels) << c.code;
    if (c.levels <= 4) {  // the box's tree is deeper than 4
      EXPECT_EQ(r.coherence->sort.pth_levels, c.levels) << c.code;
    }
  }
  // --pth-levels alone sets the default layout's pth width; with a --code that agrees it is fine
  s.sort.code.clear();
  for (std::uint32_t levels : {1u, 3u}) {
    s.sort.pth_levels = levels;
    const RenderResult r = render_scene(path, s);
    expect_bitwise_equal(reference, r, "--pth-levels");
    ASSERT_TRUE(r.coherence);
    EXPECT_EQ(r.coherence->sort.pth_levels, levels);
  }
  s.sort.code = "pth:3,dir:8";
  const RenderResult from_code = render_scene(path, s);
  ASSERT_TRUE(from_code.coherence);
  EXPECT_EQ(from_code.coherence->sort.pth_levels, 3u);
}

TEST(Methods, CodeAndPthLevelsThatDisagreeAreAnInputError) {
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 1;
  s.method = "pth";
  s.sort.code = "origin:8,pth:4,dir:8";
  s.sort.pth_levels = 6;
  EXPECT_THROW(render_scene(shipped_scene("cornell-box.gltf"), s), InputError);
  EXPECT_EQ(requested_pth_levels("pth:4", 0), 4u);
  EXPECT_EQ(requested_pth_levels("", 7), 7u);
  EXPECT_EQ(requested_pth_levels("paper", 0), 10u);
  EXPECT_EQ(requested_pth_levels("origin-first", 5), 5u);  // no pth part: --pth-levels decides
  EXPECT_EQ(layout_pth_levels("origin-first"), 0u);
  EXPECT_EQ(requested_pth_levels("", 0), layout_pth_levels(default_code_layout(true)));  // the default's width
}

// Layouts of at most 32 bits are sorted as 32-bit keys (pth_walk_and_code32, a 32-bit radix sort),
// wider ones as 64-bit keys; either way the image is naive's, so the sort kept every slot.
TEST(Methods, KeyWidthFollowsTheLayoutAndImagesStayBitForBit) {
  RenderSettings s = small_box_settings(5u);
  s.sort.sort_from_bounce = 1;
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult reference = render_scene(path, s);
  struct Case {
    const char* method;
    const char* code;
    std::uint32_t key_bits;
  };
  for (const Case& c : {Case{"hash", "origin-first", 32}, Case{"hash", "two-point", 30}, Case{"pth", "pth-32", 31},
                        Case{"hash", "end:10,dir:1", 32}, Case{"hash", "origin-uniform:8,end:2,dir:1", 32},
                        Case{"pth", "origin:4,end:4,pth:2,dir:1", 30}, Case{"hash", "origin:8,end:3,dir:1", 35},
                        Case{"pth", "paper", 60}, Case{"hash", "hash", 40}}) {
    s.method = c.method;
    s.sort.code = c.code;
    const RenderResult r = render_scene(path, s);
    expect_bitwise_equal(reference, r, c.code);
    ASSERT_TRUE(r.coherence) << c.code;
    EXPECT_EQ(r.coherence->key_bits, c.key_bits) << c.code;
  }
  // the defaults fit 32 bits
  s.sort.code.clear();
  for (const char* method : {"hash", "pth"}) {
    s.method = method;
    const RenderResult r = render_scene(path, s);
    expect_bitwise_equal(reference, r, method);
    ASSERT_TRUE(r.coherence) << method;
    EXPECT_EQ(r.coherence->sort.code, default_code_layout(s.method == "pth"));
    EXPECT_LE(r.coherence->key_bits, 32u) << method;
  }
}

TEST(Methods, TwoPointLayoutsPlaceTheEndPointBelowTheOrigin) {
  const Bounds box{{0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}};
  const CodeParams c = parse_code_layout("two-point", 0, box);
  EXPECT_EQ(c.key_bits, 30u);
  EXPECT_EQ(c.origin_bits, 5u);
  EXPECT_EQ(c.origin_adaptive, 0u);
  EXPECT_EQ(c.origin_shift, 15u);
  EXPECT_EQ(c.end_bits, 5u);
  EXPECT_EQ(c.end_shift, 0u);
  const CodeParams d = parse_code_layout("dir:2,end:3,origin:1", 0, box);
  EXPECT_EQ(d.key_bits, 16u);
  EXPECT_EQ(d.direction_shift, 12u);
  EXPECT_EQ(d.end_shift, 3u);
  EXPECT_EQ(d.origin_shift, 0u);
}

// --sort-from-bounce B: bounces before B trace unsorted through `extend`, B and later are sorted;
// the image never depends on B.
TEST(Methods, SortFromBounceKeepsImagesBitForBit) {
  RenderSettings s = small_box_settings(9u);
  s.rr_depth = 2;
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult reference = render_scene(path, s);
  EXPECT_EQ(s.sort.sort_from_bounce, 3u);  // where sorting paid on the H200
  for (const char* method : {"hash", "pth"}) {
    for (std::uint32_t from : {1u, 2u, 3u, 1000u}) {
      s.method = method;
      s.sort.sort_from_bounce = from;
      const RenderResult r = render_scene(path, s);
      const std::string what = fmt::format("{} from bounce {}", method, from);
      expect_bitwise_equal(reference, r, what.c_str());
      ASSERT_TRUE(r.coherence) << what;
      EXPECT_EQ(r.coherence->sort.sort_from_bounce, from);
      // the walk's launches carry the method's name; extend's "extend"
      const bool walked = r.kernel_seconds.count(method) != 0, extended = r.kernel_seconds.count("extend") != 0;
      EXPECT_EQ(walked, from <= r.iterations.size()) << what;
      EXPECT_EQ(extended, from > 1) << what;
      ASSERT_GE(r.iterations.size(), 3u);
      for (std::size_t i = 0; i < r.iterations.size(); ++i) {
        const auto& k = r.iterations[i].kernel_seconds;
        EXPECT_EQ(k.count(method) != 0, i + 1 >= from) << what << ", bounce " << i + 1;
        EXPECT_EQ(k.count("extend") != 0, i + 1 < from) << what << ", bounce " << i + 1;
      }
    }
  }
}

TEST(Methods, MalformedCodeLayoutsAreInputErrors) {
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 1;
  s.method = "pth";
  for (const char* code : {"origin:11", "pth", "dir:8,colour:3", "origin:10,pth:16,dir:16", "papers", "end:11", "end",
                           "end:x", "end:-1", "origin:10,end:10,dir:3"}) {
    s.sort.code = code;
    EXPECT_THROW(render_scene(shipped_scene("cornell-box.gltf"), s), InputError) << code;
  }
}

// auto: the other methods take turns at the first launches (a screen at a quarter wave, the
// megakernel on every 8th row of one sample, then a full wave for at most three methods within
// 0.9x of the screen's best), the fastest the rest. Naive's image
// whatever it picks: the probe's launches are part of the image.
TEST(Methods, AutoRendersTheNaiveImageWithTheFastestProbedMethod) {
  RenderSettings s = small_box_settings(4u);
  ProbeShare share("8");  // the screen (7 spp) is at most an eighth of the render: it probes
  s.spp = 64;
  s.wavefront_size = 2 * s.width * s.height;  // a wave of 2 samples per pixel: the screen takes 1
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult reference = render_scene(path, s);
  s.method = "auto";
  const RenderResult r = render_scene(path, s);
  expect_bitwise_equal(reference, r, "auto");
  EXPECT_EQ(r.samples, 64u);
  EXPECT_EQ(r.passes, reference.passes) << "the probe splits launches, not passes";
  const AutoChoice& a = r.auto_choice;
  ASSERT_EQ(a.probe_rays_per_second.size(), methods().size() - 1) << "every other method screened";
  EXPECT_EQ(a.probe_rays_per_second.count("auto"), 0u);
  double fastest_screen = 0;
  for (const auto& [name, rate] : a.probe_rays_per_second) {
    EXPECT_GT(rate, 0.0) << name;
    fastest_screen = std::max(fastest_screen, rate);
  }
  // the device's default is in the final whatever its screen; the others within 0.9x of the best
  const std::string fallback = device_default_method(select_device("").is_gpu);
  for (const auto& [name, rate] : a.final_rays_per_second) {
    if (name != fallback) {
      EXPECT_GE(a.probe_rays_per_second.at(name), 0.9 * fastest_screen) << name << " should have been screened out";
    }
    EXPECT_GT(rate, 0.0) << name;
  }
  // the pick: the default, unless another method of the final beat it by 5 % at least (auto_pick)
  if (!a.final_rays_per_second.empty()) {
    EXPECT_EQ(a.final_rays_per_second.count(fallback), 1u) << "the default runs in the final";
    ASSERT_EQ(a.final_rays_per_second.count(a.method), 1u) << a.method;
    if (a.method != fallback) {
      EXPECT_GT(a.final_rays_per_second.at(a.method), 1.05 * a.final_rays_per_second.at(fallback));
    }
    EXPECT_NE(a.final_rays_per_second.size(), 1u) << "a final round of one method times nothing";
    EXPECT_LE(a.final_rays_per_second.size(), 4u) << "the default and at most the screen's three fastest";
  }
  EXPECT_FALSE(a.reason.empty());
  EXPECT_GT(a.probe_seconds, 0.0);
  EXPECT_GE(r.render_seconds, a.probe_seconds);
  // the pick's own figures: a wavefront pick reports the shared pool
  if (find_method(a.method).wavefront) {
    EXPECT_EQ(r.wavefront.slots, std::size_t(s.wavefront_size));
    EXPECT_FALSE(r.iterations.empty());
  }
}

// A render too short for the whole screen: only the first methods probe, a launch each (here a
// time-bounded render, whose length auto cannot know), and the image is still naive's.
TEST(Methods, AutoWithFewerLaunchesThanMethodsProbesTheFirstOnes) {
  RenderSettings s = small_box_settings(6u);
  s.pass_samples = 1;  // passes of one sample: one launch each
  s.method = "auto";
  s.spp = 0;  // until stopped: after 3 passes
  RenderControl control;
  std::uint32_t checks = 0;
  control.stop_requested = [&] { return ++checks > 3; };
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult r = render_scene(path, s, control);
  ASSERT_EQ(r.passes, 3u);
  s.method = "naive";
  s.spp = r.samples;
  expect_bitwise_equal(render_scene(path, s), r, "auto with 3 launches");
  // a launch each: naive, wavefront, sc (every 8th row of 32x24 is too few pixels to screen on)
  EXPECT_EQ(r.auto_choice.probe_rays_per_second.size(), 3u);
  EXPECT_FALSE(r.auto_choice.screen_rows);
  EXPECT_TRUE(r.auto_choice.final_rays_per_second.empty());
  EXPECT_EQ(r.auto_choice.probe_rays_per_second.count(r.auto_choice.method), 1u);
  EXPECT_EQ(r.auto_choice.reason, "the fastest of the probe");
}

// An image whose every 8th row holds 4096 pixels: the megakernel screens on those rows of one
// sample and wavefront renders the other rows of it, and the image is still naive's.
TEST(Methods, AutoScreensTheMegakernelOnEveryEighthRow) {
  RenderSettings s = small_box_settings(8u);
  s.width = 256;
  s.height = 128;
  ProbeShare share("8");
  s.spp = 48;  // the screen: 1 + 5 spp, an eighth of the render
  s.wavefront_size = s.width * s.height;
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult reference = render_scene(path, s);
  s.method = "auto";
  const RenderResult r = render_scene(path, s);
  expect_bitwise_equal(reference, r, "auto, rows screen");
  EXPECT_TRUE(r.auto_choice.screen_rows);
  EXPECT_EQ(r.auto_choice.probe_rays_per_second.size(), methods().size() - 1);
}

// A render whose screen would take more than a 256th of its samples on a CPU (an eighth on a GPU)
// takes the device's default without probing (on a CPU, the megakernel): a 3-spp render on PoCL.
TEST(Methods, AutoTakesTheDevicesDefaultForAShortRender) {
  RenderSettings s = small_box_settings(6u);
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult reference = render_scene(path, s);
  s.method = "auto";
  const RenderResult r = render_scene(path, s);
  expect_bitwise_equal(reference, r, "auto, short render");
  // the megakernel on a CPU (PoCL in CI), sc+rg on a GPU
  EXPECT_EQ(r.auto_choice.method, device_default_method(select_device("").is_gpu));
  EXPECT_NE(r.auto_choice.reason.find("too short to probe"), std::string::npos) << r.auto_choice.reason;
  EXPECT_TRUE(r.auto_choice.probe_rays_per_second.empty());
  EXPECT_EQ(r.auto_choice.probe_seconds, 0.0);
}

TEST(Methods, UnknownMethodIsAnInputError) {
  EXPECT_THROW(find_method("teleport"), InputError);
  EXPECT_EQ(method_names().size(), methods().size());
}

TEST(Methods, StreamCompactionLaunchesOnlyLivePaths) {
  // with compaction the per-bounce live counts fall; every bounce's rays are at most the pool size
  RenderSettings s;
  s.width = s.height = 24;
  s.spp = 4;
  s.rr_depth = 2;
  s.method = "sc";
  const RenderResult r = render_scene(shipped_scene("cornell-box.gltf"), s);
  ASSERT_GE(r.iterations.size(), 3u);
  EXPECT_GT(r.iterations.front().live_paths, r.iterations.back().live_paths);
  std::uint64_t rays = 0;
  for (const auto& it : r.iterations) rays += it.live_paths + it.shadow_rays;
  EXPECT_EQ(rays, r.rays);
}

}  // namespace

// Voxel geometry: every face in an integer plane, so paths leave faces at concave corners with
// their origins in split planes that hold flat faces. Every tree and every method gives the naive
// image on the deep KD-tree bit for bit, for several seeds (kernels/common/accel/kdtree_traverse.h,
// kd_inner_step: an origin in the plane visits the side it does not go into too).
namespace {

// Every tree and every method gives the naive image on the deep KD-tree bit for bit, for `seeds`.
void expect_every_tree_and_method_agrees(const std::filesystem::path& path, std::initializer_list<std::uint32_t> seeds,
                                         std::optional<glm::vec3> environment = std::nullopt) {
  const ClContext cl(select_device(""));
  const ProgramCache cache(ProgramCache::default_directory());
  std::vector<PreparedScene> prepared;
  std::vector<DeviceScene> scenes;
  for (const NamedTree& t : every_tree()) {
    prepared.push_back(prepare_scene(path, t.choice));
    scenes.push_back(upload_scene(cl, prepared.back().tree, prepared.back().tables, prepared.back().bvh()));
  }
  for (const std::uint32_t seed : seeds) {
    RenderSettings s;
    s.width = 32;
    s.height = 32;
    s.spp = 4;
    s.seed = seed;
    s.environment = environment;
    const RenderResult reference = render(cl, cache, scenes[0], prepared[0].camera, s);
    for (std::size_t t = 0; t < scenes.size(); ++t) {
      for (const char* method : {"naive", "sc+rg", "hash", "pth"}) {
        if (device_cannot_sort(method)) continue;
        if (!every_tree()[t].sorts && (std::string(method) == "hash" || std::string(method) == "pth")) continue;
        s.method = method;
        const RenderResult other = render(cl, cache, scenes[t], prepared[t].camera, s);
        const std::string what =
            fmt::format("{}: seed {}, {} on {}", path.filename().string(), seed, method, every_tree()[t].name);
        expect_bitwise_equal(reference, other, what.c_str());
      }
    }
  }
}

}  // namespace

TEST(Methods, VoxelTerrainIsTheSameOnEveryTreeAndMethod) {
  expect_every_tree_and_method_agrees(shipped_scene("voxel-terrain.gltf"), {1u, 3u, 7u});
}

// An absorbing glass block (KHR_materials_volume, the Mitsuba reference scene): the path's medium and
// the segment lengths inside it agree on every tree and method.
TEST(Methods, GlassVolumeIsTheSameOnEveryTreeAndMethod) {
  const auto path = std::filesystem::path(COHORT_SOURCE_DIR) / "scenes/reference/glass-volume.gltf";
  ASSERT_TRUE(prepare_scene(path).tables.features.volume);
  expect_every_tree_and_method_agrees(path, {1u, 5u}, glm::vec3(0.1f));
}

namespace {

// A shipped scene on the two trees the paired walks are checked between: the 8-wide BVH with float
// planes (on a CPU the naive kernel pairs its walks there) and the 4-wide BVH (no pairs); with
// `white_sky`, the scene of the white-sky workload (apply_white_sky: one grey Lambertian, the
// framing camera; the settings' part is the caller's).
struct PairedTreeScenes {
  PreparedScene wide, four;
  DeviceScene wide_scene, four_scene;
  PairedTreeScenes(const ClContext& cl, const std::filesystem::path& path, bool white_sky = false)
      : wide(prepared(path, TreeChoice{.kd = KdBuildOptions{}, .bvh8f = true}, white_sky)),
        four(prepared(path, TreeChoice{KdBuildOptions{}, true}, white_sky)),
        wide_scene(upload_scene(cl, wide.tree, wide.tables, wide.bvh())),
        four_scene(upload_scene(cl, four.tree, four.tables, four.bvh())) {}

 private:
  static PreparedScene prepared(const std::filesystem::path& path, const TreeChoice& trees, bool white_sky) {
    PreparedScene p = prepare_scene(path, trees);
    RenderSettings unused;
    if (white_sky) apply_white_sky(p, unused);
    return p;
  }
};

// Naive on the 4-wide BVH (the reference), then naive (paired on a CPU) and sc+rg (one walk per ray)
// on the 8-wide BVH with float planes, through `camera` with settings `s` (the method set here): each
// bit for bit the reference. Returns the paired render.
RenderResult expect_paired_as_reference(const ClContext& cl, const ProgramCache& cache, const PairedTreeScenes& t,
                                        const SceneCamera& camera, RenderSettings s, const std::string& what) {
  s.method = "naive";
  const RenderResult reference = render(cl, cache, t.four_scene, camera, s);
  RenderResult paired = render(cl, cache, t.wide_scene, camera, s);
  s.method = "sc+rg";
  const RenderResult single = render(cl, cache, t.wide_scene, camera, s);
  expect_bitwise_equal(reference, paired, ("paired naive: " + what).c_str());
  expect_bitwise_equal(reference, single, ("sc+rg: " + what).c_str());
  return paired;
}

}  // namespace

// On a CPU device the naive megakernel traces two samples' paths in lock step on the 8-wide BVH with
// float planes (-DCOHORT_PAIRED_WALKS; kernels/common/wavefront/pathtrace.h, trace_paths_paired): each
// path must still be what a walk of its own gives. Passes of an odd number of samples end with one
// path alone; Russian roulette from the second segment and an alpha-masked scene end the two paths of
// a pair at different segments. The reference is naive on the 4-wide BVH (no pairs) and sc+rg on the
// same tree (one walk per ray).
TEST(Methods, PairedWalksGiveEachPathItsOwnWalksImage) {
  const ClContext cl(select_device(""));
  if (!device_support(cl.info()).paired_walks) GTEST_SKIP() << cl.info().name << " runs no paired walks";
  const ProgramCache cache(ProgramCache::default_directory());
  for (const char* scene : {"cornell-box.gltf", "reference/alpha-mask.gltf"}) {
    const PairedTreeScenes trees(cl, shipped_scene(scene));
    for (const std::uint32_t pass_samples : {0u, 1u, 3u}) {
      RenderSettings s;
      s.width = 24;
      s.height = 20;
      s.spp = 7;
      s.seed = 5;
      s.rr_depth = 2;
      s.pass_samples = pass_samples;
      const std::string what = fmt::format("{}, passes of {} samples", scene, pass_samples);
      const RenderResult paired = expect_paired_as_reference(cl, cache, trees, trees.wide.camera, s, what);
      double sum = 0.0;
      for (const float v : paired.image.rgb) sum += v;
      EXPECT_GT(sum, 0.0) << what << ": a black image proves nothing";
    }
  }
}

// Where the program is Lambertian-only and no shadow ray or roulette follows the camera hits, the
// paired naive kernel shades a batch's camera hits eight to a vector (kernels/common/wavefront/
// shade_batch.h): each path's state must still be path_shade's, bit for bit. The Cornell box without
// NEE (camera rays that meet its one-sided light add its emission at the hit; roulette from the
// second segment), in passes of 3 samples too (lanes past the batch's paths); the white-sky workload
// from outside (lanes that miss) with 5 segments and with 1 (every path ends at its camera hit).
// From inside the box (an interior view) the paths go on bounce by bounce, their bounce hits shaded
// eight to a vector too where no roulette follows them (trace_paths_diffuse): roulette from the
// fourth segment, so that rounds of both kinds run, and the white-sky workload.
TEST(Methods, DiffuseCameraHitsShadedSideBySide) {
  const ClContext cl(select_device(""));
  if (!device_support(cl.info()).paired_walks) GTEST_SKIP() << cl.info().name << " runs no paired walks";
  const ProgramCache cache(ProgramCache::default_directory());
  const PairedTreeScenes box(cl, shipped_scene("cornell-box.gltf"));
  ASSERT_TRUE(box.wide.tables.features.names().empty()) << "the Cornell box is no longer Lambertian-only";
  const auto small = [](std::uint32_t width, std::uint32_t height, std::uint32_t spp, std::uint32_t seed) {
    RenderSettings s;
    s.width = width;
    s.height = height;
    s.spp = spp;
    s.seed = seed;
    return s;
  };
  for (const std::uint32_t pass_samples : {0u, 3u}) {
    RenderSettings s = small(24, 20, 9, 11);
    s.nee = false;
    s.rr_depth = 2;
    s.pass_samples = pass_samples;
    expect_paired_as_reference(cl, cache, box, box.wide.camera, s,
                               fmt::format("Cornell box without NEE, passes of {} samples", pass_samples));
  }
  const PairedTreeScenes white(cl, shipped_scene("cornell-box.gltf"), true);
  for (const std::uint32_t segments : {5u, 1u}) {
    RenderSettings s = small(32, 24, 8, 2);
    apply_white_sky_settings(s);
    s.max_depth = segments;
    const RenderResult paired = expect_paired_as_reference(cl, cache, white, white.wide.camera, s,
                                                           fmt::format("white sky, {} segments", segments));
    double sum = 0.0;
    for (const float v : paired.image.rgb) sum += v;
    EXPECT_GT(sum, 0.0) << "a black image proves nothing";
  }
  const Bounds& b = box.wide_scene.bounds;
  const glm::vec3 lo(b.lo.x, b.lo.y, b.lo.z), hi(b.hi.x, b.hi.y, b.hi.z);
  const auto inside_box = [&](const glm::vec3& p) {
    return glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi));
  };
  ASSERT_FALSE(inside_box(box.wide.camera.eye)) << "the views above must be exterior ones";
  SceneCamera inside = box.wide.camera;
  inside.eye = 0.5f * (lo + hi);
  inside.target = inside.eye + glm::normalize(box.wide.camera.target - box.wide.camera.eye);
  for (const std::uint32_t pass_samples : {0u, 3u}) {
    RenderSettings s = small(24, 20, 9, 5);
    s.nee = false;
    s.rr_depth = 4;
    s.pass_samples = pass_samples;
    expect_paired_as_reference(cl, cache, box, inside, s,
                               fmt::format("inside the Cornell box without NEE, passes of {} samples", pass_samples));
  }
  RenderSettings s = small(32, 24, 8, 7);
  apply_white_sky_settings(s);
  const RenderResult paired = expect_paired_as_reference(cl, cache, white, inside, s, "inside, white sky");
  double sum = 0.0;
  for (const float v : paired.image.rgb) sum += v;
  EXPECT_GT(sum, 0.0) << "inside, white sky: a black image proves nothing";
}

// The paired naive kernel gives a pixel that no ray of it can meet the scene through (the background
// of a view from afar, camera_pixel_misses_box) its sky sample by sample without tracing: the same
// bits as the naive kernel that traces every sample (4-wide BVH) and as sc+rg, under a coloured
// sky, with the scene small in the frame so that most pixels are such pixels.
TEST(Methods, BackgroundPixelsGiveTheTracedImage) {
  const ClContext cl(select_device(""));
  if (!device_support(cl.info()).paired_walks) GTEST_SKIP() << cl.info().name << " runs no paired walks";
  const ProgramCache cache(ProgramCache::default_directory());
  const PairedTreeScenes trees(cl, shipped_scene("reference/alpha-mask.gltf"));
  // from afar and aslant, the scene's box a few tens of degrees wide in a 45-degree frame
  const Bounds& b = trees.wide_scene.bounds;
  const glm::vec3 lo(b.lo.x, b.lo.y, b.lo.z), hi(b.hi.x, b.hi.y, b.hi.z);
  SceneCamera far;
  far.target = 0.5f * (lo + hi);
  far.eye = far.target + 1.6f * glm::length(hi - lo) * glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f));
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.spp = 9;
  s.seed = 3;
  s.environment = glm::vec3(0.7f, 0.9f, 1.3f);
  expect_paired_as_reference(cl, cache, trees, far, s, "with background pixels");
  const CameraParams cam = make_camera_params(far, s.width, s.height);
  int background = 0;
  for (std::uint32_t y = 0; y < s.height; ++y)
    for (std::uint32_t x = 0; x < s.width; ++x)
      background += camera_pixel_misses_box(&cam, s.width, s.height, x, y, v3(b.lo.x, b.lo.y, b.lo.z),
                                            v3(b.hi.x, b.hi.y, b.hi.z));
  EXPECT_GT(background, int(s.width * s.height) / 2) << "the view must have a background for the test to mean anything";
  EXPECT_LT(background, int(s.width * s.height)) << "and the scene in it";
}
