// The OpenCL build options every program gets (runtime/cl/kernel_program.h): the software prefetch of
// the BVH walk (kernels/common/core/port.h, co_prefetch, whose form the compiler's own macros choose) only
// on devices whose local memory is the cached global memory (device_support), never on Oclgrind
// (which checks, not times) nor on a GPU with a scratchpad (which hides the latency with other warps).
// That the walk's hits do not change with it is TraceKernel.Bvh4* on the CPU device. The naive
// megakernel's paired walks (two samples' paths in lock step) only on PoCL's CPU driver, whose work items
// run as scalar code of their own, and on Oclgrind (so that its checks cover them); that they change no
// bit is Methods.PairedWalks*. The box tests' fused slabs (one fma each) where the device has a
// hardware fma, except on OpenCL GPUs and Oclgrind (-DCOHORT_UNFUSED_SLABS); that neither form changes a
// hit is TraceKernel.Bvh* on PoCL (fused) and scripts/test-oclgrind (unfused). On GPUs and Oclgrind the
// branch-free descend, the min/max instructions of the naive and trace programs' box tests
// (-DCOHORT_GPU_MINMAX) and the pixel tiles (-DCOHORT_PIXEL_TILES), which scripts/test-oclgrind renders
// to PoCL's bits.
#include <gtest/gtest.h>

#include "runtime/backend/device_support.h"
#include "runtime/cl/kernel_program.h"

using namespace cohort;

namespace {

DeviceInfo device(const char* platform, bool cpu) {
  DeviceInfo d;
  d.platform_name = platform;
  d.is_cpu = cpu;
  d.is_gpu = !cpu;
  d.local_memory_is_global = cpu;
  return d;
}

// Whether the options every program gets on `d` define `define`.
bool builds_with(const DeviceInfo& d, const char* define) {
  return base_build_options(d).find(define) != std::string::npos;
}

bool prefetches(const DeviceInfo& d) { return builds_with(d, "-DCOHORT_PREFETCH"); }
bool pairs(const DeviceInfo& d) { return builds_with(d, "-DCOHORT_PAIRED_WALKS"); }
bool unfused(const DeviceInfo& d) { return builds_with(d, "-DCOHORT_UNFUSED_SLABS"); }

}  // namespace

TEST(BuildOptions, PairedWalksOnPoclsCpuDriverAndOclgrind) {
  EXPECT_TRUE(pairs(device("Portable Computing Language", true)));
  EXPECT_TRUE(pairs(device("Oclgrind", true)));
  // runtimes that pack work items into SIMD lanes: pairs made them several times slower
  EXPECT_FALSE(pairs(device("Intel(R) OpenCL", true)));
  EXPECT_FALSE(pairs(device("rusticl", true)));
  DeviceInfo pocl_gpu = device("Portable Computing Language", false);  // PoCL's CUDA or Level Zero driver
  EXPECT_FALSE(pairs(pocl_gpu));
  EXPECT_FALSE(pairs(device("NVIDIA CUDA", false)));
  DeviceInfo gpu_like_cpu = device("Some runtime", true);
  gpu_like_cpu.local_memory_is_global = false;
  EXPECT_FALSE(pairs(gpu_like_cpu));
}

TEST(BuildOptions, FusedSlabsWhereTheCpuHasAnFmaAndOnCuda) {
  EXPECT_FALSE(unfused(device("Portable Computing Language", true)));
  EXPECT_FALSE(unfused(device("Intel(R) OpenCL", true)));
  EXPECT_TRUE(unfused(device("NVIDIA CUDA", false)));  // NVIDIA's OpenCL traced diffuse rays slower fused
  EXPECT_TRUE(unfused(device("Oclgrind", true)));      // CI checks the unfused form there
  DeviceInfo no_fma = device("Portable Computing Language", true);
  no_fma.fma = false;  // a software fma would cost more than it saves
  EXPECT_TRUE(unfused(no_fma));
  DeviceInfo cuda = device("CUDA", false);
  EXPECT_TRUE(device_support(cuda).fused_slabs);  // the CUDA backend always fuses (every NVIDIA GPU has an fma)
}

// The GPU's forms: the branch-free descend, the min/max instructions of the naive and trace programs'
// box tests, and camera rays in 8x4 pixel tiles
TEST(BuildOptions, GpuFormsOnGpusAndOclgrind) {
  for (const char* define : {"-DCOHORT_BRANCH_FREE_DESCEND", "-DCOHORT_GPU_MINMAX", "-DCOHORT_PIXEL_TILES"}) {
    EXPECT_TRUE(builds_with(device("NVIDIA CUDA", false), define)) << define;
    EXPECT_TRUE(builds_with(device("Portable Computing Language", false), define)) << define;  // PoCL's GPU drivers
    EXPECT_TRUE(builds_with(device("Oclgrind", true), define)) << define;  // CI checks the GPU's form there
    EXPECT_FALSE(builds_with(device("Portable Computing Language", true), define)) << define;
    EXPECT_FALSE(builds_with(device("Intel(R) OpenCL", true), define)) << define;
    EXPECT_FALSE(builds_with(device("rusticl", true), define)) << define;
  }
  const DeviceSupport cuda = device_support(device("CUDA", false));  // the CUDA build takes all three
  EXPECT_TRUE(cuda.branch_free_descend);
  EXPECT_TRUE(cuda.gpu_minmax);
  EXPECT_TRUE(cuda.pixel_tiles);
}

TEST(BuildOptions, PrefetchWhereLocalMemoryIsTheCache) {
  EXPECT_TRUE(prefetches(device("Portable Computing Language", true)));
  EXPECT_TRUE(prefetches(device("Intel(R) OpenCL", true)));
  EXPECT_TRUE(prefetches(device("rusticl", true)));  // port.h gives it OpenCL C's prefetch()
  EXPECT_FALSE(prefetches(device("Oclgrind", true)));
  EXPECT_FALSE(prefetches(device("NVIDIA CUDA", false)));
  DeviceInfo gpu_like_cpu = device("Some runtime", true);
  gpu_like_cpu.local_memory_is_global = false;  // a scratchpad: the decision is not "is a CPU"
  EXPECT_FALSE(prefetches(gpu_like_cpu));
}

TEST(BuildOptions, AlwaysOpenClC12) {
  for (const DeviceInfo& d : {device("Portable Computing Language", true), device("NVIDIA CUDA", false)})
    EXPECT_EQ(base_build_options(d).rfind("-cl-std=CL1.2", 0), 0u) << base_build_options(d);
}
