// host_kernel(): unpacks DeviceKernel arguments into a host kernel's parameters.
#pragma once

#include <cstring>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace cohort::test {

unsigned char* host_bytes(const DeviceBuffer& b);

namespace detail {

// Local memory of one launch: one work item at a time, so one allocation per argument suffices.
struct LocalScratch {
  std::vector<std::unique_ptr<unsigned char[]>> blocks;
};

template <class T>
T unpack(const KernelArg& a, LocalScratch& scratch) {
  if constexpr (std::is_pointer_v<T>) {
    if (const auto* b = std::get_if<DeviceBuffer>(&a)) return reinterpret_cast<T>(host_bytes(*b));
    if (const auto* m = std::get_if<LocalMemory>(&a)) {
      scratch.blocks.push_back(std::make_unique<unsigned char[]>(m->bytes));
      return reinterpret_cast<T>(scratch.blocks.back().get());
    }
    throw std::invalid_argument("host kernel: a pointer parameter needs a buffer or local memory");
  } else {
    const auto* v = std::get_if<ValueArg>(&a);
    if (!v || v->bytes.size() != sizeof(T)) throw std::invalid_argument("host kernel: value argument of the wrong size");
    T value;
    std::memcpy(&value, v->bytes.data(), sizeof(T));
    return value;
  }
}

}  // namespace detail

template <class... Params>
HostKernelFunction host_kernel(void (*entry)(Params...)) {
  return [entry](const std::vector<KernelArg>& args) {
    if (args.size() != sizeof...(Params)) throw std::invalid_argument("host kernel: wrong argument count");
    detail::LocalScratch scratch;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      std::tuple<std::decay_t<Params>...> values{detail::unpack<std::decay_t<Params>>(args[I], scratch)...};
      std::apply(entry, values);
    }(std::index_sequence_for<Params...>{});
  };
}

}  // namespace cohort::test
