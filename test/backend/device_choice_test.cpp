// --device over a backend's list (runtime/backend/device_choice.h): the rules are the same for any
// list, so a made-up one tests them without a driver.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "runtime/backend/device_choice.h"
#include "runtime/util/error.h"

using namespace cohort;

namespace {

DeviceInfo device(std::size_t index, const std::string& name, const std::string& platform, bool gpu) {
  DeviceInfo d;
  d.device_index = index;
  d.name = name;
  d.platform_name = platform;
  d.is_gpu = gpu;
  d.is_cpu = !gpu;
  return d;
}

// A CPU first, then two identical GPUs of another platform.
const std::vector<DeviceInfo> kDevices = {device(0, "cpu-haswell", "Portable Computing Language", false),
                                          device(1, "NVIDIA H200", "NVIDIA CUDA", true),
                                          device(2, "NVIDIA H200", "NVIDIA CUDA", true)};

// $COHORT_DEVICE unset for each test, as the empty spec reads it.
class DeviceChoice : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* v = std::getenv("COHORT_DEVICE")) saved_ = v;
    unsetenv("COHORT_DEVICE");
  }
  void TearDown() override {
    if (saved_) setenv("COHORT_DEVICE", saved_->c_str(), 1);
  }
  std::optional<std::string> saved_;
};

std::vector<std::size_t> indices(const std::vector<DeviceInfo>& devices) {
  std::vector<std::size_t> out;
  for (const auto& d : devices) out.push_back(d.device_index);
  return out;
}

TEST_F(DeviceChoice, EmptySpecPrefersAGpuThenTheEnvironment) {
  EXPECT_EQ(select_device(kDevices, "").device_index, 1u);
  EXPECT_EQ(select_device({kDevices[0]}, "").device_index, 0u);  // no GPU: the CPU
  setenv("COHORT_DEVICE", "haswell", 1);
  EXPECT_EQ(select_device(kDevices, "").device_index, 0u);
  EXPECT_EQ(select_device(kDevices, "2").device_index, 2u);  // an explicit spec wins over the environment
}

TEST_F(DeviceChoice, IndexOrNameSubstringOfDeviceOrPlatform) {
  EXPECT_EQ(select_device(kDevices, "2").device_index, 2u);
  EXPECT_EQ(select_device(kDevices, "portable").device_index, 0u);  // platform name, any case
  EXPECT_EQ(select_device(kDevices, "h200").device_index, 1u);
  EXPECT_THROW(select_device(kDevices, "3"), InputError);
  EXPECT_THROW(select_device(kDevices, "amd"), InputError);
  EXPECT_THROW(select_device({}, ""), InputError);
}

TEST_F(DeviceChoice, SeveralDevices) {
  EXPECT_EQ(indices(select_devices(kDevices, "all")), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(indices(select_devices(kDevices, "all:nvidia")), (std::vector<std::size_t>{1, 2}));
  // a repeated name takes the next device that matches
  EXPECT_EQ(indices(select_devices(kDevices, "nvidia,nvidia")), (std::vector<std::size_t>{1, 2}));
  EXPECT_EQ(indices(select_devices(kDevices, "2,0")), (std::vector<std::size_t>{2, 0}));
  // one GPU per MPI rank of a machine, modulo the matches
  EXPECT_EQ(indices(select_devices(kDevices, "rank:nvidia", 0)), (std::vector<std::size_t>{1}));
  EXPECT_EQ(indices(select_devices(kDevices, "rank:nvidia", 1)), (std::vector<std::size_t>{2}));
  EXPECT_EQ(indices(select_devices(kDevices, "rank:nvidia", 2)), (std::vector<std::size_t>{1}));
  EXPECT_THROW(select_devices(kDevices, "1,1"), InputError);               // listed twice
  EXPECT_THROW(select_devices(kDevices, "nvidia,nvidia,nvidia"), InputError);  // no third match
  EXPECT_THROW(select_devices(kDevices, "0,"), InputError);                // an empty item
  EXPECT_THROW(select_devices(kDevices, "all:amd"), InputError);
}

}  // namespace
