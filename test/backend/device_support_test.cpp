// Launch sizes and what Cohort does on a device, from the limits it reports
// (runtime/backend/device.h, launch_group; runtime/backend/device_support.h).
#include <gtest/gtest.h>

#include "runtime/backend/device.h"
#include "runtime/backend/device_support.h"

using namespace cohort;

TEST(LaunchGroup, DefaultIsSixtyFourWhereTheKernelAllowsIt) {
  EXPECT_EQ(launch_group(4096, 8, 0), 64u);   // PoCL
  EXPECT_EQ(launch_group(1024, 32, 0), 64u);  // NVIDIA
  EXPECT_EQ(launch_group(256, 64, 0), 64u);   // AMD GCN
}

TEST(LaunchGroup, ShrinksToTheKernelsLimitDownToOne) {
  EXPECT_EQ(launch_group(32, 8, 0), 32u);
  EXPECT_EQ(launch_group(16, 8, 0), 16u);
  EXPECT_EQ(launch_group(12, 8, 0), 8u);  // a multiple of the preferred size where one fits
  EXPECT_EQ(launch_group(6, 8, 0), 6u);   // else what the kernel allows
  EXPECT_EQ(launch_group(1, 8, 0), 1u);
  EXPECT_EQ(launch_group(0, 0, 0), 1u);   // a driver that reports nothing still launches
}

TEST(LaunchGroup, APreferredMultipleAboveSixtyFourWins) {
  EXPECT_EQ(launch_group(1024, 128, 0), 128u);
  EXPECT_EQ(launch_group(100, 128, 0), 100u);
}

TEST(LaunchGroup, WantedSizesAreKeptWithinTheLimit) {
  EXPECT_EQ(launch_group(4096, 8, 32), 32u);  // the speculative vote's group
  EXPECT_EQ(launch_group(16, 8, 32), 16u);
  EXPECT_EQ(launch_group(256, 32, 256), 256u);  // the sort's compiled size, checked by its builder
}

TEST(DeviceSupport, ParsesTheOpenClCVersion) {
  EXPECT_EQ(parse_opencl_c_version("OpenCL C 1.2 PoCL"), 102);
  EXPECT_EQ(parse_opencl_c_version("OpenCL C 3.0 "), 300);
  EXPECT_EQ(parse_opencl_c_version("OpenCL C 1.1"), 101);
  EXPECT_EQ(parse_opencl_c_version(""), 0);
  EXPECT_EQ(parse_opencl_c_version("garbage"), 0);
}

TEST(DeviceSupport, RefusesDevicesBelowOpenClC12WithTheReason) {
  DeviceInfo d;
  d.name = "Old GPU";
  d.opencl_c_version = "OpenCL C 1.1";
  const DeviceSupport s = device_support(d);
  EXPECT_FALSE(s.runs);
  EXPECT_NE(s.refusal.find("Old GPU"), std::string::npos);
  EXPECT_NE(s.refusal.find("1.1"), std::string::npos);
  d.opencl_c_version = "OpenCL C 1.2";
  EXPECT_TRUE(device_support(d).runs);
  d.opencl_c_version.clear();  // CUDA devices
  EXPECT_TRUE(device_support(d).runs);
}

TEST(DeviceSupport, PthLevelsFitTheLocalBudget) {
  DeviceInfo rusticl;  // llvmpipe: 32 KiB of cached local memory, all usable
  rusticl.local_memory = 32 * 1024;
  rusticl.local_memory_is_global = true;
  EXPECT_EQ(device_support(rusticl).local_budget, 32u * 1024);
  EXPECT_EQ(device_support(rusticl).pth_levels, 10u);  // 1023 nodes of 8 bytes
  DeviceInfo gpu;  // a scratchpad: half of it, for two groups per compute unit
  gpu.local_memory = 48 * 1024;
  EXPECT_EQ(device_support(gpu).local_budget, 24u * 1024);
  EXPECT_EQ(device_support(gpu).pth_levels, 10u);
  gpu.local_memory = 4 * 1024;  // 2 KiB: 255 nodes, 8 levels
  EXPECT_EQ(device_support(gpu).pth_levels, 8u);
  EXPECT_TRUE(device_support(gpu).runs);
}

TEST(DeviceSupport, WorkGroupFollowsTheDevicesLimit) {
  DeviceInfo d;
  d.max_work_group = 16;
  EXPECT_EQ(device_support(d).work_group, 16u);
  d.max_work_group = 4096;
  EXPECT_EQ(device_support(d).work_group, 64u);
}

TEST(DeviceSupport, MesasOpenClRunsNoSortingMethod) {
  DeviceInfo d;
  d.name = "llvmpipe (LLVM 15.0.6, 256 bits)";
  d.platform_name = "rusticl";
  const DeviceSupport s = device_support(d);
  EXPECT_TRUE(s.runs);
  EXPECT_FALSE(s.sorts);
  EXPECT_NE(s.sort_refusal.find("llvmpipe"), std::string::npos);
  d.platform_name = "Portable Computing Language";
  EXPECT_TRUE(device_support(d).sorts);
}
