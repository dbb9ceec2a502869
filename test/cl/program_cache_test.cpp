#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "runtime/cl/cl_error.h"
#include "runtime/cl/context.h"
#include "runtime/backend/embedded_sources.h"
#include "runtime/cl/kernel_program.h"
#include "runtime/backend/program_cache.h"

namespace fs = std::filesystem;
using namespace cohort;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("cohort-test-" + std::to_string(std::random_device{}()));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

ClContext cpu_context() { return ClContext(select_device("")); }

}  // namespace

TEST(EmbeddedSources, ExpandsIncludesOnce) {
  const std::string src = expand_kernel_source("naive.cl");
  EXPECT_NE(src.find("render_naive"), std::string::npos);
  EXPECT_EQ(src.find("#include \""), std::string::npos);
  // types.h is reached through several headers but appears once
  const auto first = src.find("#line 1 \"common/core/types.h\"");
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(src.find("#line 1 \"common/core/types.h\"", first + 1), std::string::npos);
  EXPECT_THROW(expand_kernel_source("no-such-file.cl"), std::runtime_error);
}

TEST(ProgramCache, ColdThenWarmThenCorruptedEntryIsRebuilt) {
  TempDir dir;
  const ClContext cl = cpu_context();
  const ProgramCache cache(dir.path);
  const ProgramBuild cold = build_kernel_program(cl, cache, "trace.cl");
  EXPECT_FALSE(cold.from_cache);
  ASSERT_TRUE(fs::exists(cold.cache_file));

  const ProgramBuild warm = build_kernel_program(cl, cache, "trace.cl");
  EXPECT_TRUE(warm.from_cache);
  EXPECT_NO_THROW(cl::Kernel(warm.program, "trace_rays"));

  // flip bytes in the payload: the checksum must catch it and the entry is rebuilt and replaced
  {
    std::fstream f(cold.cache_file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(cold.cache_file) - 16));
    f.write("CORRUPTCORRUPT!!", 16);
  }
  const ProgramBuild rebuilt = build_kernel_program(cl, cache, "trace.cl");
  EXPECT_FALSE(rebuilt.from_cache);
  EXPECT_NO_THROW(cl::Kernel(rebuilt.program, "trace_rays"));
  EXPECT_TRUE(build_kernel_program(cl, cache, "trace.cl").from_cache);

  // a truncated entry is not trusted either
  fs::resize_file(cold.cache_file, 40);
  EXPECT_FALSE(build_kernel_program(cl, cache, "trace.cl").from_cache);
}

TEST(ProgramCache, KeyDependsOnOptionsSourceAndDevice) {
  // moved in, not assigned from literals: GCC 12 reports a false -Wrestrict on those at -O3
  const auto device = [](std::string driver) {
    DeviceInfo d;
    d.name = std::string("A");
    d.driver_version = std::move(driver);
    return d;
  };
  const DeviceInfo a = device("1"), b = device("2");
  EXPECT_NE(ProgramCache::key(a, "src", ""), ProgramCache::key(b, "src", ""));
  EXPECT_NE(ProgramCache::key(a, "src", ""), ProgramCache::key(a, "src2", ""));
  EXPECT_NE(ProgramCache::key(a, "src", ""), ProgramCache::key(a, "src", "-DX"));
  TempDir dir;
  const ClContext cl = cpu_context();
  const ProgramCache cache(dir.path);
  EXPECT_FALSE(build_kernel_program(cl, cache, "trace.cl", "-DCOHORT_TEST_A").from_cache);
  EXPECT_FALSE(build_kernel_program(cl, cache, "trace.cl", "-DCOHORT_TEST_B").from_cache);
  EXPECT_TRUE(build_kernel_program(cl, cache, "trace.cl", "-DCOHORT_TEST_A").from_cache);
}

TEST(ProgramCache, BuildErrorNamesTheCallAndCarriesTheLog) {
  const ClContext cl = cpu_context();
  const ProgramCache cache(std::nullopt);
  try {
    build_cl_program(cl, cache, "__kernel void broken( { }", "");
    FAIL() << "expected a build failure";
  } catch (const DeviceError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("clBuildProgram"), std::string::npos) << msg;
    EXPECT_NE(msg.find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << msg;
  }
}

TEST(ProgramCache, NaiveKernelCompiles) {
  const ClContext cl = cpu_context();
  const ProgramCache cache(std::nullopt);
  const ProgramBuild b = build_kernel_program(cl, cache, "naive.cl");
  EXPECT_NO_THROW(cl::Kernel(b.program, "render_naive"));
}

// A device builds each program once: a second request (another method of one --method auto render)
// gets the same program object back at no cost; other defines are another program.
TEST(ProgramCache, ADeviceBuildsEachProgramOnce) {
  TempDir dir;
  const ClContext cl = cpu_context();
  const ProgramCache cache(dir.path);
  const Device& device = cl;
  const DeviceProgram first = device.build_program(cache, "film");
  const DeviceProgram again = device.build_program(cache, "film");
  EXPECT_EQ(again.object, first.object);
  EXPECT_TRUE(again.from_cache);
  EXPECT_EQ(again.seconds, 0.0);
  const DeviceProgram other = device.build_program(cache, "film", "-DCOHORT_TEST_A");
  EXPECT_NE(other.object, first.object);
  // kernels of the shared program are separate objects: their arguments do not mix
  EXPECT_NE(first.kernel("film_add").object(), again.kernel("film_add").object());
}
