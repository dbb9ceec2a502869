// The OpenCL backend behind Device: a driver's error leaves it as DeviceError naming the OpenCL call
// and error (what main() reports), never as cl::Error, which code above the backend cannot name.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "runtime/cl/context.h"

using namespace cohort;

namespace {

// Runs `call`, which must fail in the driver, and returns the DeviceError's message.
template <class Call>
std::string device_error_of(Call&& call) {
  try {
    call();
  } catch (const DeviceError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a DeviceError: " << e.what();
    return {};
  }
  ADD_FAILURE() << "the call did not fail";
  return {};
}

}  // namespace

TEST(ClDevice, DriverErrorsLeaveAsDeviceErrorsNamingTheCall) {
  const ClContext context(select_device(""));
  const Device& device = context;
  const DeviceBuffer small = device.allocate("small", 16);
  const DeviceBuffer large = device.allocate("large", 64);
  std::vector<unsigned char> host(64);
  // each reaches past the end of the 16-byte buffer: CL_INVALID_VALUE from the driver
  const std::string read = device_error_of([&] { device.read(small, 0, host.size(), host.data()); });
  EXPECT_NE(read.find("clEnqueueReadBuffer"), std::string::npos) << read;
  EXPECT_NE(read.find("CL_INVALID_VALUE"), std::string::npos) << read;
  const std::string write = device_error_of([&] { device.write(small, 8, host.size(), host.data()); });
  EXPECT_NE(write.find("clEnqueueWriteBuffer"), std::string::npos) << write;
  const std::string copy = device_error_of([&] { device.copy(large, small, large.size()); });
  EXPECT_NE(copy.find("clEnqueueCopyBuffer"), std::string::npos) << copy;
  const std::string fill = device_error_of([&] { device.fill(small, 0u, 16); });
  EXPECT_NE(fill.find("clEnqueueFillBuffer"), std::string::npos) << fill;
  // the queue still works after the errors
  const std::vector<std::uint32_t> words = {1, 2, 3, 4};
  device.write(small, 0, 16, words.data());
  std::vector<std::uint32_t> back(4);
  device.read(small, 0, 16, back.data());
  EXPECT_EQ(back, words);
}
