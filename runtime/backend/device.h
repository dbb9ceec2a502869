// The backend interface: what the renderers, the sort and the tracing tools need from a device
// (buffers, programs built from the embedded kernels with the scene's feature defines, launches with
// arguments and work-group sizes, timed events, reads and writes). OpenCL (runtime/cl, ClContext)
// and CUDA (runtime/cuda) implement it; the kernels behind it are the same shared headers.
//
// The interface is header only; the backends share device choice, the embedded kernel sources and
// the program cache (the rest of runtime/backend), and never link each other.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "runtime/backend/device_info.h"
#include "runtime/util/error.h"

namespace cohort {

class ProgramCache;

// Backends report every failure of the device or its driver as DeviceError (runtime/util/error.h),
// naming the call, the error and what it was for; their own error types stay inside them.

// A backend's own buffer object (cl::Buffer, CUdeviceptr).
class BufferObject {
 public:
  virtual ~BufferObject() = default;
};

// A device buffer with shared ownership, as cl::Buffer: copies refer to the same memory.
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  DeviceBuffer(std::shared_ptr<BufferObject> object, std::size_t bytes) : object_(std::move(object)), bytes_(bytes) {}
  std::size_t size() const { return bytes_; }
  BufferObject* object() const { return object_.get(); }
  explicit operator bool() const { return object_ != nullptr; }

 private:
  std::shared_ptr<BufferObject> object_;
  std::size_t bytes_ = 0;
};

// A kernel's dynamically sized local (CUDA: shared) array, CO_LOCAL_PARAM in kernels/common/core/port.h:
// an argument in OpenCL, the launch's dynamic shared memory in CUDA.
struct LocalMemory {
  std::size_t bytes = 0;
};

// A scalar or struct argument, by value.
struct ValueArg {
  std::vector<unsigned char> bytes;
};

using KernelArg = std::variant<std::monostate, DeviceBuffer, LocalMemory, ValueArg>;

// A backend's own kernel object (cl::Kernel, CUfunction).
class KernelObject {
 public:
  virtual ~KernelObject() = default;
  // The most work items one work-group of this kernel may have on its device.
  virtual std::size_t max_group() const = 0;
  // The group-size multiple the device runs best (OpenCL: the kernel's preferred work-group size
  // multiple; CUDA: the warp).
  virtual std::size_t group_multiple() const = 0;
};

// The work items a launch that leaves the size to the kernel aims at: two warps of 32 (NVIDIA), one
// wavefront of 64 (AMD), eight AVX2 vectors (PoCL). Measured no slower than other sizes on PoCL and
// the H200 (docs/vendors.md).
inline constexpr std::size_t kDefaultGroup = 64;

// The work-group size of a launch: `wanted` items (0: kDefaultGroup, or the preferred multiple when
// that is larger, rounded down to the multiple) within the most the kernel allows on its device, and
// never below 1. Kernels with a group-wide step work at every size (docs/vendors.md), so a device
// that allows fewer items (a small GPU, PoCL under POCL_MAX_WORK_GROUP_SIZE) only gets smaller groups.
inline std::size_t launch_group(std::size_t max_group, std::size_t multiple, std::size_t wanted) {
  max_group = std::max<std::size_t>(max_group, 1);
  multiple = std::max<std::size_t>(multiple, 1);
  if (wanted != 0) return std::min(wanted, max_group);
  std::size_t group = std::min(std::max(kDefaultGroup, multiple), max_group);
  if (group >= multiple) group -= group % multiple;
  return group;
}

// A kernel and the arguments of its next launch, set by index in the order of the kernel's OpenCL
// parameter list.
class DeviceKernel {
 public:
  DeviceKernel() = default;
  DeviceKernel(std::shared_ptr<KernelObject> object, std::string name) : object_(std::move(object)), name_(std::move(name)) {}

  void set_arg(std::size_t index, const DeviceBuffer& b) { slot(index) = b; }
  void set_arg(std::size_t index, const LocalMemory& m) { slot(index) = m; }
  template <class T>
  void set_arg(std::size_t index, const T& value) {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>, "kernel arguments are copied by value");
    ValueArg v;
    v.bytes.resize(sizeof(T));
    std::memcpy(v.bytes.data(), &value, sizeof(T));
    slot(index) = std::move(v);
  }
  template <class... Args>
  void set_args(const Args&... args) {
    std::size_t i = 0;
    (set_arg(i++, args), ...);
  }

  const std::vector<KernelArg>& args() const { return args_; }
  KernelObject* object() const { return object_.get(); }
  const std::string& name() const { return name_; }
  std::size_t max_group() const { return object_->max_group(); }
  // The size of a launch of this kernel that wants `wanted` items per group (launch_group).
  std::size_t launch_group(std::size_t wanted = 0) const {
    return cohort::launch_group(object_->max_group(), object_->group_multiple(), wanted);
  }

 private:
  KernelArg& slot(std::size_t index) {
    if (args_.size() <= index) args_.resize(index + 1);
    return args_[index];
  }
  std::shared_ptr<KernelObject> object_;
  std::string name_;
  std::vector<KernelArg> args_;
};

// A backend's own record of one command (cl::Event, a pair of CUevents).
class EventObject {
 public:
  virtual ~EventObject() = default;
  virtual void wait() = 0;
  virtual double seconds() = 0;  // device time of the command; waits for it
};

class DeviceEvent {
 public:
  DeviceEvent() = default;
  explicit DeviceEvent(std::shared_ptr<EventObject> object) : object_(std::move(object)) {}
  void wait() const {
    if (object_) object_->wait();
  }
  double seconds() const { return object_ ? object_->seconds() : 0.0; }

 private:
  std::shared_ptr<EventObject> object_;
};

// A backend's own compiled program (cl::Program, CUmodule).
class ProgramObject {
 public:
  virtual ~ProgramObject() = default;
  virtual DeviceKernel kernel(const std::string& name) const = 0;
};

struct DeviceProgram {
  std::shared_ptr<ProgramObject> object;
  bool from_cache = false;  // warm: loaded from a cached binary
  double seconds = 0;       // compile (cold) or load (warm) time
  DeviceKernel kernel(const std::string& name) const { return object->kernel(name); }
};

enum class Backend { opencl, cuda };

// How kernels use a buffer: a hint some drivers place memory by.
enum class Access { read_write, read_only };

inline const char* backend_name(Backend b) { return b == Backend::cuda ? "cuda" : "opencl"; }

class Device {
 public:
  virtual ~Device() = default;
  virtual Backend backend() const = 0;
  virtual const DeviceInfo& info() const = 0;

  // A buffer of `bytes` (at least 1), filled from `data` when given. Throws DeviceError naming
  // `what` and the sizes when the device cannot hold it.
  virtual DeviceBuffer allocate(const std::string& what, std::size_t bytes, const void* data = nullptr,
                                Access access = Access::read_write) const = 0;

  // Builds the embedded program `name` ("naive", "wavefront", "pth", "trace", "radix_sort",
  // "film": kernels/NAME.cl or kernels/cuda/NAME.cu) with `defines`, a space-separated list of
  // -DNAME[=VALUE] (the scene's -DCOHORT_FEATURE_* defines, the sort's sizes), through the cache;
  // once per device: a later call with the same name and defines gets the same program (kernels are
  // still made anew from it) at no cost, as --method auto needs when it sets up every method in one
  // render (loading a cached binary took ~5 ms per program on the H200).
  DeviceProgram build_program(const ProgramCache& cache, const std::string& name,
                              const std::string& defines = {}) const {
    const std::string key = name + '\n' + defines;
    const std::lock_guard lock(programs_->mutex);
    if (const auto it = programs_->built.find(key); it != programs_->built.end())
      return DeviceProgram{it->second, true, 0.0};
    DeviceProgram program = compile_program(cache, name, defines);
    programs_->built.emplace(key, program.object);
    return program;
  }
  // The options every program of this device is compiled with, besides `defines` (for the record).
  virtual std::string compile_options() const { return {}; }

  // Runs `kernel` over `items` work items in work-groups of kernel.launch_group(group) items (0: the
  // kernel's own size; items rounded up to a multiple of it), in order after every earlier command.
  // Nothing runs for 0 items. A kernel whose work-group size is fixed at compile time (the radix
  // sort's) is launched with exactly that size, which its builder checks against the kernel's limit.
  DeviceEvent launch(const DeviceKernel& kernel, std::size_t items, std::size_t group = 0) const {
    if (items == 0) return {};
    return enqueue(kernel, items, kernel.launch_group(group));
  }

  // Commands run in the order they were issued. A non-blocking write reads `data` later: it must
  // outlive the command.
  virtual void write(const DeviceBuffer& to, std::size_t offset, std::size_t bytes, const void* data,
                     bool blocking = true) const = 0;
  virtual void read(const DeviceBuffer& from, std::size_t offset, std::size_t bytes, void* data) const = 0;
  virtual DeviceEvent copy(const DeviceBuffer& from, const DeviceBuffer& to, std::size_t bytes) const = 0;
  // Sets `count` 32-bit words from the start of `to` to `value`.
  virtual void fill(const DeviceBuffer& to, std::uint32_t value, std::size_t count) const = 0;
  virtual void finish() const = 0;

 protected:
  // launch with the group size settled.
  virtual DeviceEvent enqueue(const DeviceKernel& kernel, std::size_t items, std::size_t group) const = 0;
  // build_program's first call for a name and defines: compile, or load the cache's binary.
  virtual DeviceProgram compile_program(const ProgramCache& cache, const std::string& name,
                                        const std::string& defines) const = 0;

 private:
  struct Programs {
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<ProgramObject>> built;
  };
  std::shared_ptr<Programs> programs_ = std::make_shared<Programs>();
};

}  // namespace cohort
