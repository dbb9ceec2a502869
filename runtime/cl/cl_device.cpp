// ClContext as the OpenCL implementation of the backend interface.
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "runtime/cl/cl_error.h"
#include "runtime/cl/context.h"
#include "runtime/cl/kernel_program.h"

namespace cohort {
namespace {

struct ClBufferObject : BufferObject {
  cl::Buffer buffer;
  explicit ClBufferObject(cl::Buffer b) : buffer(std::move(b)) {}
};

std::size_t kernel_max_group(const cl::Kernel& kernel, const cl::Device& device) {
  return translate_cl_errors([&] { return kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device); });
}

std::size_t kernel_group_multiple(const cl::Kernel& kernel, const cl::Device& device) {
  return translate_cl_errors(
      [&] { return kernel.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(device); });
}

struct ClKernelObject : KernelObject {
  cl::Kernel kernel;
  cl::Device device;
  ClKernelObject(cl::Kernel k, cl::Device d) : kernel(std::move(k)), device(std::move(d)) {}
  std::size_t max_group() const override { return kernel_max_group(kernel, device); }
  std::size_t group_multiple() const override { return kernel_group_multiple(kernel, device); }
};

struct ClProgramObject : ProgramObject {
  cl::Program program;
  cl::Device device;
  ClProgramObject(cl::Program p, cl::Device d) : program(std::move(p)), device(std::move(d)) {}
  DeviceKernel kernel(const std::string& name) const override {
    try {
      return DeviceKernel(std::make_shared<ClKernelObject>(cl::Kernel(program, name.c_str()), device), name);
    } catch (const cl::Error& e) {
      throw DeviceError(describe(e, name));
    }
  }
};

struct ClEventObject : EventObject {
  cl::Event event;
  explicit ClEventObject(cl::Event e) : event(std::move(e)) {}
  void wait() override {
    translate_cl_errors([&] { event.wait(); });
  }
  double seconds() override {
    return translate_cl_errors([&] {
      event.wait();
      return event_seconds(event);
    });
  }
};

DeviceEvent wrap_event(const cl::Event& e) { return DeviceEvent(std::make_shared<ClEventObject>(e)); }

}  // namespace

std::size_t cl_launch_group(const cl::Kernel& kernel, const cl::Device& device, std::size_t wanted) {
  return launch_group(kernel_max_group(kernel, device), kernel_group_multiple(kernel, device), wanted);
}

const cl::Buffer& cl_buffer(const DeviceBuffer& b) {
  const auto* object = dynamic_cast<const ClBufferObject*>(b.object());
  if (!object) throw std::invalid_argument("not an OpenCL buffer");
  return object->buffer;
}

DeviceBuffer ClContext::allocate(const std::string& what, std::size_t bytes, const void* data, Access access) const {
  const cl_mem_flags flags = access == Access::read_only ? CL_MEM_READ_ONLY : CL_MEM_READ_WRITE;
  return DeviceBuffer(std::make_shared<ClBufferObject>(buffer(what, bytes, data, flags)), std::max<std::size_t>(bytes, 1));
}

DeviceProgram ClContext::compile_program(const ProgramCache& cache, const std::string& name,
                                       const std::string& defines) const {
  const ProgramBuild build = build_kernel_program(*this, cache, name + ".cl", defines);
  DeviceProgram p;
  p.object = std::make_shared<ClProgramObject>(build.program, cl_device);
  p.from_cache = build.from_cache;
  p.seconds = build.seconds;
  return p;
}

std::string ClContext::compile_options() const { return base_build_options(device); }

DeviceEvent ClContext::enqueue(const DeviceKernel& kernel, std::size_t items, std::size_t group) const {
  auto* object = static_cast<ClKernelObject*>(kernel.object());
  cl::Kernel& k = object->kernel;
  const auto& args = kernel.args();
  try {
    for (cl_uint i = 0; i < args.size(); ++i) {
      const KernelArg& a = args[i];
      if (const auto* b = std::get_if<DeviceBuffer>(&a)) k.setArg(i, cl_buffer(*b));
      else if (const auto* m = std::get_if<LocalMemory>(&a)) k.setArg(i, cl::Local(m->bytes));
      else if (const auto* v = std::get_if<ValueArg>(&a)) k.setArg(i, v->bytes.size(), v->bytes.data());
      else throw std::invalid_argument(fmt::format("{}: argument {} is not set", kernel.name(), i));
    }
    cl::Event event;
    queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange((items + group - 1) / group * group), cl::NDRange(group),
                               nullptr, &event);
    return wrap_event(event);
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, kernel.name()));
  }
}

void ClContext::write(const DeviceBuffer& to, std::size_t offset, std::size_t bytes, const void* data,
                      bool blocking) const {
  // Oclgrind's uninitialised-value check (21.10) forgets the rest of a buffer written in part (the
  // queue counters are): there the whole buffer is read, patched and written back
  translate_cl_errors([&] {
    if (is_oclgrind(device) && (offset != 0 || bytes != to.size())) {
      std::vector<unsigned char> whole(to.size());
      queue.enqueueReadBuffer(cl_buffer(to), CL_TRUE, 0, whole.size(), whole.data());
      std::memcpy(whole.data() + offset, data, bytes);
      queue.enqueueWriteBuffer(cl_buffer(to), CL_TRUE, 0, whole.size(), whole.data());
      return;
    }
    queue.enqueueWriteBuffer(cl_buffer(to), blocking ? CL_TRUE : CL_FALSE, offset, bytes, data);
  });
}

void ClContext::read(const DeviceBuffer& from, std::size_t offset, std::size_t bytes, void* data) const {
  translate_cl_errors([&] { queue.enqueueReadBuffer(cl_buffer(from), CL_TRUE, offset, bytes, data); });
}

DeviceEvent ClContext::copy(const DeviceBuffer& from, const DeviceBuffer& to, std::size_t bytes) const {
  return translate_cl_errors([&] {
    cl::Event event;
    queue.enqueueCopyBuffer(cl_buffer(from), cl_buffer(to), 0, 0, bytes, nullptr, &event);
    return wrap_event(event);
  });
}

void ClContext::fill(const DeviceBuffer& to, std::uint32_t value, std::size_t count) const {
  if (!count) return;
  // Oclgrind's uninitialised-value check does not see clEnqueueFillBuffer (21.10): there the words
  // come from the host, so scripts/test-oclgrind reports only what the kernels leave unset
  translate_cl_errors([&] {
    if (is_oclgrind(device)) {
      const std::vector<std::uint32_t> words(count, value);
      queue.enqueueWriteBuffer(cl_buffer(to), CL_TRUE, 0, count * sizeof(value), words.data());
      return;
    }
    queue.enqueueFillBuffer(cl_buffer(to), value, 0, count * sizeof(value));
  });
}

void ClContext::finish() const {
  translate_cl_errors([&] { queue.finish(); });
}

}  // namespace cohort
