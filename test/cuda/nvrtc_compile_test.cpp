// Every CUDA program compiles with NVRTC as the CUDA backend compiles it at run time (same sources,
// defines and rounding flags), for the H100's architecture. NVRTC needs no GPU, so this runs in CI.
#include <gtest/gtest.h>

#include <string>

#include "kernels/test_kernels.h"
#include "runtime/backend/embedded_sources.h"
#include "runtime/cuda/nvrtc_compile.h"
#include "runtime/util/error.h"

using namespace cohort;

namespace {

// Compiles `name` for sm_90, or skips when NVRTC cannot be loaded here.
void compile(const std::string& name, const std::string& defines) {
  const auto options = nvrtc_options(9, 0, defines);
  std::string cubin;
  try {
    cubin = nvrtc_compile(name, expand_test_kernel_source("cuda/" + name + ".cu"), options);
  } catch (const InputError& e) {
    GTEST_SKIP() << "NVRTC is not available: " << e.what();
  }
  EXPECT_GT(cubin.size(), 1000u) << name;
  EXPECT_EQ(cubin.substr(0, 4), "\x7f" "ELF") << name << ": a CUBIN is an ELF image";
}

const char* kAllFeatures =
    "-DCOHORT_FEATURE_TEXTURES -DCOHORT_FEATURE_CONDUCTOR -DCOHORT_FEATURE_DIELECTRIC -DCOHORT_FEATURE_PLASTIC -DCOHORT_FEATURE_VOLUME "
    "-DCOHORT_FEATURE_CLEARCOAT -DCOHORT_FEATURE_SHEEN -DCOHORT_FEATURE_SPECULAR";

}  // namespace

TEST(NvrtcCompile, RenderingProgramsWithEveryFeatureSet) {
  for (const char* name : {"naive", "wavefront", "pth"}) {
    compile(name, "");  // a diffuse-only scene
    compile(name, kAllFeatures);
  }
  // the clearcoat's own normal map and TEXCOORD_1 lookups
  compile("naive", std::string(kAllFeatures) + " -DCOHORT_FEATURE_NORMAL_MAP -DCOHORT_FEATURE_TEXCOORD1");
}

// The 4-wide BVH (--tree bvh4) is written once too: every program that traces through it compiles
// for CUDA, with and without the material features.
TEST(NvrtcCompile, ProgramsTracingTheBvh4) {
  for (const char* name : {"naive", "wavefront", "trace", "aov", "pth"}) compile(name, "-DCOHORT_ACCEL_BVH4");
  compile("naive", std::string(kAllFeatures) + " -DCOHORT_ACCEL_BVH4");
}

// The compressed 8-wide BVH (--tree bvh8) likewise, in every program but pth (hash and pth walk the
// KD-tree or the 4-wide BVH; pth_kernels.h stops a build with COHORT_ACCEL_BVH8).
TEST(NvrtcCompile, ProgramsTracingTheBvh8) {
  for (const char* name : {"naive", "wavefront", "trace", "aov"}) compile(name, "-DCOHORT_ACCEL_BVH8");
  compile("naive", std::string(kAllFeatures) + " -DCOHORT_ACCEL_BVH8");
}

// The 8-wide BVH with float planes (--tree bvh8f) likewise: its float8 helpers' lane-by-lane CUDA
// form (port.h), in every program but pth.
TEST(NvrtcCompile, ProgramsTracingTheBvh8f) {
  for (const char* name : {"naive", "wavefront", "trace", "aov"}) compile(name, "-DCOHORT_ACCEL_BVH8F");
  compile("naive", std::string(kAllFeatures) + " -DCOHORT_ACCEL_BVH8F");
}

TEST(NvrtcCompile, TracingAndTestPrograms) {
  compile("trace", "");
  compile("film", "");
  compile("bsdf_test", kAllFeatures);
}

TEST(NvrtcCompile, RadixSortTilings) {
  // the GPU tilings the sort picks on a 48 KiB device, and a one-item tiling without local exchange
  compile("radix_sort", "-DSORT_WG=256 -DSORT_ITEMS=13 -DSORT_LOCAL_EXCHANGE=1 -DSORT_KEY64=0");
  compile("radix_sort", "-DSORT_WG=256 -DSORT_ITEMS=9 -DSORT_LOCAL_EXCHANGE=1 -DSORT_KEY64=1");
  compile("radix_sort", "-DSORT_WG=1 -DSORT_ITEMS=64 -DSORT_LOCAL_EXCHANGE=0 -DSORT_KEY64=1");
}

TEST(NvrtcCompile, OptionsCarryTheRoundingOfOpenCl) {
  const auto o = nvrtc_options(9, 0, "-DA -DB=2");
  const std::vector<std::string> want = {"--gpu-architecture=sm_90", "--std=c++17", "--fmad=false", "--prec-div=true",
                                         "--prec-sqrt=true", "--ftz=false", "-DA", "-DB=2"};
  EXPECT_EQ(o, want);
}
