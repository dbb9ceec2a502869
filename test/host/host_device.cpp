#include "host/host_device.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "kernels/common/core/port.h"

namespace cohort::test {
namespace {

struct HostBuffer : BufferObject {
  std::vector<co_float4> storage;  // 16-byte aligned, as device buffers are
  explicit HostBuffer(std::size_t bytes) : storage((bytes + 15) / 16) {}
};

struct HostKernel : KernelObject {
  HostKernelFunction run;
  std::size_t max_group() const override { return 1; }
  std::size_t group_multiple() const override { return 1; }
};

struct HostProgramObject : ProgramObject {
  const HostProgram* program = nullptr;
  DeviceKernel kernel(const std::string& name) const override {
    const auto it = program->kernels.find(name);
    if (it == program->kernels.end()) throw std::invalid_argument("host program has no kernel " + name);
    auto k = std::make_shared<HostKernel>();
    k->run = it->second;
    return DeviceKernel(std::move(k), name);
  }
};

// The defines other than the scene's features, which the host build compiles in (all of them).
std::string fixed_defines(const std::string& defines) {
  std::istringstream in(defines);
  std::string out;
  for (std::string word; in >> word;)
    if (!word.starts_with("-DCOHORT_FEATURE_")) out += (out.empty() ? "" : " ") + word;
  return out;
}

}  // namespace

unsigned char* host_bytes(const DeviceBuffer& b) {
  auto* object = dynamic_cast<HostBuffer*>(b.object());
  if (!object) throw std::invalid_argument("not a host buffer");
  return reinterpret_cast<unsigned char*>(object->storage.data());
}

HostDevice::HostDevice() {
  info_.platform_name = "host";
  info_.name = "host C++ (one work item per work-group)";
  info_.is_cpu = true;
  info_.compute_units = 1;
  info_.local_memory = 1u << 20;
  info_.local_memory_is_global = true;
  info_.global_memory = 1ull << 32;
  info_.max_allocation = 1ull << 32;
  info_.max_work_group = 1;
  info_.correctly_rounded_divide_sqrt = true;
}

DeviceBuffer HostDevice::allocate(const std::string&, std::size_t bytes, const void* data, Access) const {
  bytes = std::max<std::size_t>(bytes, 1);
  auto b = std::make_shared<HostBuffer>(bytes);
  if (data) std::memcpy(b->storage.data(), data, bytes);
  return DeviceBuffer(std::move(b), bytes);
}

DeviceProgram HostDevice::compile_program(const ProgramCache&, const std::string& name,
                                        const std::string& defines) const {
  const bool key32 = defines.find("-DSORT_KEY64=0") != std::string::npos;
  const HostProgram& program =
      name != "radix_sort" ? host_render_program() : key32 ? host_sort32_program() : host_sort64_program();
  if (fixed_defines(defines) != program.defines)
    throw std::invalid_argument(fmt::format("host program {} is compiled with \"{}\", not \"{}\"", name,
                                            program.defines, fixed_defines(defines)));
  auto object = std::make_shared<HostProgramObject>();
  object->program = &program;
  DeviceProgram p;
  p.object = std::move(object);
  return p;
}

DeviceEvent HostDevice::enqueue(const DeviceKernel& kernel, std::size_t items, std::size_t group) const {
  // every work-group of `group` items becomes `group` work-groups of one item: the global ids stay
  const std::size_t total = (items + group - 1) / group * group;
  const auto& run = static_cast<const HostKernel*>(kernel.object())->run;
  for (std::size_t i = 0; i < total; ++i) {
    co_host_item = CoHostWorkItem{static_cast<uint32_t>(i), 0u, 1u, static_cast<uint32_t>(i)};
    run(kernel.args());
  }
  return {};
}

void HostDevice::write(const DeviceBuffer& to, std::size_t offset, std::size_t bytes, const void* data, bool) const {
  std::memcpy(host_bytes(to) + offset, data, bytes);
}

void HostDevice::read(const DeviceBuffer& from, std::size_t offset, std::size_t bytes, void* data) const {
  std::memcpy(data, host_bytes(from) + offset, bytes);
}

DeviceEvent HostDevice::copy(const DeviceBuffer& from, const DeviceBuffer& to, std::size_t bytes) const {
  std::memcpy(host_bytes(to), host_bytes(from), bytes);
  return {};
}

void HostDevice::fill(const DeviceBuffer& to, std::uint32_t value, std::size_t count) const {
  auto* p = reinterpret_cast<std::uint32_t*>(host_bytes(to));
  std::fill(p, p + count, value);
}

}  // namespace cohort::test
