// The wave size every wavefront method shares (device_pool_size), on devices described by hand.
#include <gtest/gtest.h>

#include "runtime/render/stages/path_pool.h"

namespace cohort {
namespace {

DeviceInfo gpu(std::uint32_t compute_units, std::uint64_t memory) {
  DeviceInfo d;
  d.is_gpu = true;
  d.compute_units = compute_units;
  d.global_memory = memory;
  d.max_allocation = memory / 4;
  return d;
}

TEST(PoolSize, LargeGpuHoldsAtLeastFourMillionPaths) {
  const RenderSettings s;
  const std::uint32_t h200 = device_pool_size(gpu(132, 141ull << 30), s);  // 141 GB, 132 compute units
  EXPECT_GE(h200, 4u << 20);
  EXPECT_EQ(h200, 132u * 32768u);
}

TEST(PoolSize, BoundedByAQuarterOfDeviceMemory) {
  const RenderSettings s;
  const std::uint64_t memory = 1ull << 30;  // 1 GiB: a quarter holds well under 4M slots of ~600 bytes
  const std::uint32_t slots = device_pool_size(gpu(132, memory), s);
  EXPECT_LT(slots, 132u * 32768u);
  EXPECT_GE(slots, 65536u);
  const std::uint64_t bytes_per_slot = WAVEFRONT_SLOT_BYTES + SORT_SLOT_BYTES + PTH_MAX_LEVELS * sizeof(SavedStackEntry);
  EXPECT_LE(std::uint64_t(slots) * bytes_per_slot, memory / 4);
}

TEST(PoolSize, CpuSizesStayAsTheyWere) {
  RenderSettings s;
  DeviceInfo cpu;
  cpu.is_cpu = true;
  cpu.compute_units = 2;
  cpu.global_memory = 8ull << 30;
  cpu.max_allocation = 2ull << 30;
  EXPECT_EQ(device_pool_size(cpu, s), 65536u);
  cpu.compute_units = 128;
  EXPECT_EQ(device_pool_size(cpu, s), 1u << 21);
}

TEST(PoolSize, WavefrontSizeOverrides) {
  RenderSettings s;
  s.wavefront_size = 1000;
  EXPECT_EQ(device_pool_size(gpu(132, 141ull << 30), s), 1000u);
}

}  // namespace
}  // namespace cohort
