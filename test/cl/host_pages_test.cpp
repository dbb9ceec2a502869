// A CPU device's large buffers live in host memory of 2 MiB pages (runtime/cl/host_pages.h): the
// memory is aligned and advised, the buffer holds what it was given, takes writes and reads like
// any other, and is freed with the buffer (LeakSanitizer in scripts/test-sanitize would see it).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <numeric>
#include <vector>

#include "runtime/cl/context.h"
#include "runtime/cl/host_pages.h"

using namespace cohort;

TEST(HostPages, AreAlignedAndWritable) {
  for (const std::size_t bytes : {std::size_t{1}, kHugePageBytes - 1, kHugePageBytes, 3 * kHugePageBytes + 5}) {
    void* memory = allocate_huge_pages(bytes);
    ASSERT_NE(memory, nullptr) << bytes;
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(memory) % kHugePageBytes, 0u) << bytes;
    std::memset(memory, 0xab, bytes);  // every byte asked for is there
    const auto* p = static_cast<const unsigned char*>(memory);
    EXPECT_EQ(p[0], 0xab);
    EXPECT_EQ(p[bytes - 1], 0xab);
    free_huge_pages(memory);
  }
}

// Sizes around the threshold (half a huge page) go both ways; every one must read back the
// uploaded words, then a patched range, through the device's own copy or the host pages.
TEST(HostPages, CpuBuffersKeepTheirContents) {
  const ClContext cl(select_device(""));
  if (!cl.device.is_cpu) GTEST_SKIP() << cl.device.name << " is not a CPU device";
  for (const std::size_t words : {kHugePageBytes / 8 - 1, kHugePageBytes / 8, kHugePageBytes + 3}) {
    std::vector<std::uint32_t> data(words);
    std::iota(data.begin(), data.end(), 7u);
    const DeviceBuffer b = cl.allocate("test words", words * 4, data.data(), Access::read_only);
    std::vector<std::uint32_t> back(words);
    cl.read(b, 0, words * 4, back.data());
    EXPECT_EQ(back, data) << words;
    const std::vector<std::uint32_t> patch(1000, 0xdeadbeefu);
    const DeviceBuffer rw = cl.allocate("test words", words * 4, data.data());
    cl.write(rw, 400, patch.size() * 4, patch.data());
    cl.read(rw, 0, words * 4, back.data());
    std::copy(patch.begin(), patch.end(), data.begin() + 100);
    EXPECT_EQ(back, data) << words;
  }
}

// The pages go back through the buffer's destructor callback: the driver must call callbacks when
// the last handle goes (checked with one of our own, registered after the one that frees).
TEST(HostPages, AreFreedWithTheBuffer) {
  const ClContext cl(select_device(""));
  if (!cl.device.is_cpu) GTEST_SKIP() << cl.device.name << " is not a CPU device";
  bool released = false;
  {
    cl::Buffer b = cl.buffer("test words", kHugePageBytes);
    b.setDestructorCallback([](cl_mem, void* flag) { *static_cast<bool*>(flag) = true; }, &released);
  }
  cl.queue.finish();
  EXPECT_TRUE(released);
}
