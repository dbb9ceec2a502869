#include "runtime/cuda/cuda_device.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>

#include <fmt/format.h>

#include "runtime/backend/embedded_sources.h"
#include "runtime/backend/program_cache.h"
#include "runtime/cuda/cuda_api.h"
#include "runtime/cuda/nvrtc_compile.h"
#include "runtime/util/error.h"
#include "runtime/util/hash.h"

namespace cohort {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

int attribute(const CudaDriver& cu, CUdevice d, CUdevice_attribute a) {
  int v = 0;
  cu.check(cu.cuDeviceGetAttribute(&v, a, d), "cuDeviceGetAttribute");
  return v;
}

DeviceInfo describe(const CudaDriver& cu, int ordinal) {
  CUdevice d = 0;
  cu.check(cu.cuDeviceGet(&d, ordinal), "cuDeviceGet");
  char name[256] = {};
  cu.check(cu.cuDeviceGetName(name, sizeof(name), d), "cuDeviceGetName");
  std::size_t memory = 0;
  cu.check(cu.cuDeviceTotalMem(&memory, d), "cuDeviceTotalMem");
  int driver = 0;
  cu.check(cu.cuDriverGetVersion(&driver), "cuDriverGetVersion");
  DeviceInfo info;
  info.device_index = static_cast<std::size_t>(ordinal);
  info.platform_name = "CUDA";
  info.name = name;
  info.vendor = "NVIDIA";
  info.version = fmt::format("compute capability {}.{}", attribute(cu, d, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MAJOR),
                             attribute(cu, d, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MINOR));
  info.driver_version = fmt::format("CUDA {}.{}", driver / 1000, driver % 1000 / 10);
  info.is_gpu = true;
  info.compute_units = static_cast<std::uint32_t>(attribute(cu, d, CU_DEVICE_ATTRIBUTE_MULTIPROCESSOR_COUNT));
  // what a block may use without opting in to more: the PTH subtree and the sort tiles are sized to it
  info.local_memory = static_cast<std::uint64_t>(attribute(cu, d, CU_DEVICE_ATTRIBUTE_MAX_SHARED_MEMORY_PER_BLOCK));
  info.global_memory = memory;
  info.max_allocation = memory;
  info.max_work_group = static_cast<std::size_t>(attribute(cu, d, CU_DEVICE_ATTRIBUTE_MAX_THREADS_PER_BLOCK));
  info.correctly_rounded_divide_sqrt = true;  // -prec-div=true -prec-sqrt=true
  return info;
}

struct CudaBuffer : BufferObject {
  const CudaDriver& cu;
  CUdeviceptr ptr = 0;
  CudaBuffer(const CudaDriver& d, CUdeviceptr p) : cu(d), ptr(p) {}
  ~CudaBuffer() override { cu.cuMemFree(ptr); }
};

CUdeviceptr pointer(const DeviceBuffer& b) {
  const auto* object = dynamic_cast<const CudaBuffer*>(b.object());
  if (!object) throw std::invalid_argument("not a CUDA buffer");
  return object->ptr;
}

struct CudaEvent : EventObject {
  const CudaDriver& cu;
  CUevent start = nullptr, end = nullptr;
  explicit CudaEvent(const CudaDriver& d) : cu(d) {
    cu.check(cu.cuEventCreate(&start, CU_EVENT_DEFAULT), "cuEventCreate");
    cu.check(cu.cuEventCreate(&end, CU_EVENT_DEFAULT), "cuEventCreate");
  }
  ~CudaEvent() override {
    cu.cuEventDestroy(start);
    cu.cuEventDestroy(end);
  }
  void wait() override { cu.check(cu.cuEventSynchronize(end), "cuEventSynchronize"); }
  double seconds() override {
    wait();
    float ms = 0;
    cu.check(cu.cuEventElapsedTime(&ms, start, end), "cuEventElapsedTime");
    return ms * 1e-3;
  }
};

struct CudaModule {
  const CudaDriver& cu;
  CUmodule module = nullptr;
  CudaModule(const CudaDriver& d, const std::string& cubin) : cu(d) {
    cu.check(cu.cuModuleLoadData(&module, cubin.data()), "cuModuleLoadData");
  }
  ~CudaModule() { cu.cuModuleUnload(module); }
  CudaModule(const CudaModule&) = delete;
  CudaModule& operator=(const CudaModule&) = delete;
};

struct CudaKernel : KernelObject {
  std::shared_ptr<CudaModule> module;  // keeps the function's module loaded
  CUfunction function = nullptr;
  std::size_t max_group() const override {
    int v = 0;
    module->cu.check(module->cu.cuFuncGetAttribute(&v, CU_FUNC_ATTRIBUTE_MAX_THREADS_PER_BLOCK, function),
                     "cuFuncGetAttribute");
    return static_cast<std::size_t>(v);
  }
  std::size_t group_multiple() const override { return 32; }  // the warp
};

struct CudaProgram : ProgramObject {
  std::shared_ptr<CudaModule> module;
  DeviceKernel kernel(const std::string& name) const override {
    auto k = std::make_shared<CudaKernel>();
    k->module = module;
    module->cu.check(module->cu.cuModuleGetFunction(&k->function, module->module, name.c_str()),
                     fmt::format("cuModuleGetFunction({})", name));
    return DeviceKernel(std::move(k), name);
  }
};

class CudaDevice final : public Device {
 public:
  CudaDevice(const CudaDriver& cu, int ordinal, std::uint64_t memory_limit) : cu_(cu), info_(describe(cu, ordinal)) {
    cu_.check(cu_.cuDeviceGet(&device_, ordinal), "cuDeviceGet");
    cc_major_ = attribute(cu_, device_, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MAJOR);
    cc_minor_ = attribute(cu_, device_, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MINOR);
    if (memory_limit) {
      info_.global_memory = std::min(info_.global_memory, memory_limit);
      info_.max_allocation = std::min(info_.max_allocation, memory_limit);
    }
    cu_.check(cu_.cuDevicePrimaryCtxRetain(&context_, device_), "cuDevicePrimaryCtxRetain");
    cu_.check(cu_.cuCtxSetCurrent(context_), "cuCtxSetCurrent");
    cu_.check(cu_.cuStreamCreate(&stream_, CU_STREAM_NON_BLOCKING), "cuStreamCreate");
  }
  ~CudaDevice() override {
    cu_.cuStreamSynchronize(stream_);
    cu_.cuStreamDestroy(stream_);
    cu_.cuDevicePrimaryCtxRelease(device_);
  }
  CudaDevice(const CudaDevice&) = delete;
  CudaDevice& operator=(const CudaDevice&) = delete;

  Backend backend() const override { return Backend::cuda; }
  const DeviceInfo& info() const override { return info_; }

  DeviceBuffer allocate(const std::string& what, std::size_t bytes, const void* data, Access) const override {
    bytes = std::max<std::size_t>(bytes, 1);
    if (bytes > info_.max_allocation)
      throw DeviceError(fmt::format("{} needs {} bytes in one buffer; {} allows at most {} bytes per allocation", what,
                                    bytes, info_.name, info_.max_allocation));
    CUdeviceptr ptr = 0;
    cu_.check(cu_.cuMemAlloc(&ptr, bytes), fmt::format("cuMemAlloc ({}, {} bytes)", what, bytes));
    DeviceBuffer b(std::make_shared<CudaBuffer>(cu_, ptr), bytes);
    if (data) write(b, 0, bytes, data, true);
    return b;
  }

  DeviceProgram compile_program(const ProgramCache& cache, const std::string& name,
                                const std::string& defines) const override {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string source = expand_kernel_source("cuda/" + name + ".cu");
    const auto options = nvrtc_options(cc_major_, cc_minor_, defines);
    std::string key = fmt::format("backend=cuda\ndevice={}\nversion={}\ndriver={}\nnvrtc={}\noptions=", info_.name,
                                  info_.version, info_.driver_version, nvrtc_version());
    for (const auto& o : options) key += o + ' ';
    key += fmt::format("\nsource={:016x}/{}\n", fnv1a64(source), source.size());
    DeviceProgram p;
    std::optional<std::string> cubin = cache.load(key);
    p.from_cache = cubin.has_value();
    auto program = std::make_shared<CudaProgram>();
    if (cubin) {
      try {
        program->module = std::make_shared<CudaModule>(cu_, *cubin);
      } catch (const DeviceError&) {
        cubin.reset();  // a cached CUBIN the driver rejects is rebuilt, never trusted
        p.from_cache = false;
      }
    }
    if (!cubin) {
      cubin = nvrtc_compile(name, source, options);
      program->module = std::make_shared<CudaModule>(cu_, *cubin);
      cache.store(key, *cubin);
    }
    p.object = std::move(program);
    p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return p;
  }

  std::string compile_options() const override {
    std::string joined;
    for (const auto& o : nvrtc_options(cc_major_, cc_minor_, {})) joined += (joined.empty() ? "" : " ") + o;
    return joined;
  }

  DeviceEvent enqueue(const DeviceKernel& kernel, std::size_t items, std::size_t group) const override {
    const auto& args = kernel.args();
    // CUDA takes a pointer to each argument's value; local arrays become dynamic shared memory
    std::vector<CUdeviceptr> pointers(args.size());
    std::vector<void*> params;
    std::size_t shared = 0;
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (const auto* b = std::get_if<DeviceBuffer>(&args[i])) {
        pointers[i] = pointer(*b);
        params.push_back(&pointers[i]);
      } else if (const auto* m = std::get_if<LocalMemory>(&args[i])) {
        shared += m->bytes;
      } else if (const auto* v = std::get_if<ValueArg>(&args[i])) {
        params.push_back(const_cast<unsigned char*>(v->bytes.data()));
      } else {
        throw std::invalid_argument(fmt::format("{}: argument {} is not set", kernel.name(), i));
      }
    }
    const auto* k = static_cast<const CudaKernel*>(kernel.object());
    const auto blocks = static_cast<unsigned>((items + group - 1) / group);
    auto event = std::make_shared<CudaEvent>(cu_);
    cu_.check(cu_.cuEventRecord(event->start, stream_), "cuEventRecord");
    cu_.check(cu_.cuLaunchKernel(k->function, blocks, 1, 1, static_cast<unsigned>(group), 1, 1,
                                 static_cast<unsigned>(shared), stream_, params.data(), nullptr),
              fmt::format("cuLaunchKernel ({})", kernel.name()));
    cu_.check(cu_.cuEventRecord(event->end, stream_), "cuEventRecord");
    return DeviceEvent(std::move(event));
  }

  void write(const DeviceBuffer& to, std::size_t offset, std::size_t bytes, const void* data,
             bool blocking) const override {
    // from pageable memory the copy has read `data` when the call returns, so non-blocking is safe
    cu_.check(cu_.cuMemcpyHtoDAsync(pointer(to) + offset, data, bytes, stream_), "cuMemcpyHtoDAsync");
    if (blocking) finish();
  }

  void read(const DeviceBuffer& from, std::size_t offset, std::size_t bytes, void* data) const override {
    cu_.check(cu_.cuMemcpyDtoHAsync(data, pointer(from) + offset, bytes, stream_), "cuMemcpyDtoHAsync");
    finish();
  }

  DeviceEvent copy(const DeviceBuffer& from, const DeviceBuffer& to, std::size_t bytes) const override {
    auto event = std::make_shared<CudaEvent>(cu_);
    cu_.check(cu_.cuEventRecord(event->start, stream_), "cuEventRecord");
    cu_.check(cu_.cuMemcpyDtoDAsync(pointer(to), pointer(from), bytes, stream_), "cuMemcpyDtoDAsync");
    cu_.check(cu_.cuEventRecord(event->end, stream_), "cuEventRecord");
    return DeviceEvent(std::move(event));
  }

  void fill(const DeviceBuffer& to, std::uint32_t value, std::size_t count) const override {
    if (count) cu_.check(cu_.cuMemsetD32Async(pointer(to), value, count, stream_), "cuMemsetD32Async");
  }

  void finish() const override { cu_.check(cu_.cuStreamSynchronize(stream_), "cuStreamSynchronize"); }

 private:
  const CudaDriver& cu_;
  DeviceInfo info_;
  CUdevice device_ = 0;
  CUcontext context_ = nullptr;
  CUstream stream_ = nullptr;
  int cc_major_ = 0, cc_minor_ = 0;
};

}  // namespace

std::vector<DeviceInfo> list_cuda_devices() {
  const CudaDriver& cu = cuda_driver();
  int count = 0;
  cu.check(cu.cuDeviceGetCount(&count), "cuDeviceGetCount");
  std::vector<DeviceInfo> out;
  for (int i = 0; i < count; ++i) out.push_back(describe(cu, i));
  return out;
}

std::unique_ptr<Device> open_cuda_device(const std::string& spec, std::uint64_t memory_limit) {
  const auto devices = list_cuda_devices();
  if (devices.empty()) throw InputError("--backend cuda: no CUDA GPU found");
  int ordinal = -1;
  std::size_t index = 0;
  const auto [ptr, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), index);
  if (spec.empty()) {
    ordinal = 0;
  } else if (ec == std::errc() && ptr == spec.data() + spec.size()) {
    if (index >= devices.size())
      throw InputError(fmt::format("--device {}: there are only {} CUDA GPUs", spec, devices.size()));
    ordinal = static_cast<int>(index);
  } else {
    for (const auto& d : devices)
      if (lower(d.name).find(lower(spec)) != std::string::npos) {
        ordinal = static_cast<int>(d.device_index);
        break;
      }
    if (ordinal < 0) throw InputError(fmt::format("--device {}: no CUDA GPU name matches", spec));
  }
  return std::make_unique<CudaDevice>(cuda_driver(), ordinal, memory_limit);
}

}  // namespace cohort
