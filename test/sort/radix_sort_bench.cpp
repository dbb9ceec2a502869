// Benchmark of the device radix sort over tilings, for tuning RadixSort::choose_tiling on a device.
// Disabled in the normal suite; scripts/bench-suite sort runs it. Environment (all optional):
//   COHORT_DEVICE         device, as `cohort devices` lists it (default: first GPU, else CPU)
//   COHORT_SORT_TILINGS   "default,GROUPxITEMS[/local],..." where /local stages tiles in local memory
//                         (the GPU mode) and no suffix writes pairs straight to global memory (the
//                         CPU mode); default: this device's tiling and a sweep of both modes
//   COHORT_SORT_COUNT     pairs (default 1000000)     COHORT_SORT_BITS  key bits (default 32);
//                         keys up to 32 bits are sorted as 32-bit keys, wider ones as 64-bit keys
//   COHORT_SORT_REPS      timed repetitions (default 5), after one warm-up run
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/cl/context.h"
#include "runtime/cl/devices.h"
#include "runtime/sort/radix_sort.h"
#include "sort/radix_sort_access.h"

using namespace cohort;

namespace {

// Processor seconds this process used so far (all threads): on a shared machine the wall time
// depends on other load, the processor time much less.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::uint64_t env_number(const char* name, std::uint64_t fallback) {
  const char* s = std::getenv(name);
  return s && *s ? std::strtoull(s, nullptr, 10) : fallback;
}

// One line per tiling: median and best rate over the repetitions and the device time per launch name.
void bench(const ClContext& cl, RadixSort& sort, const std::string& label, std::uint32_t n, unsigned bits, int reps) {
  std::mt19937_64 rng(1);
  const std::size_t key_bytes = sort.key_bytes();
  std::vector<unsigned char> keys(n * key_bytes);
  const std::uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint64_t k = rng() & mask;
    std::memcpy(&keys[i * key_bytes], &k, key_bytes);  // little-endian: the low bytes
  }
  std::vector<std::uint32_t> values(n);
  std::iota(values.begin(), values.end(), 0u);
  DeviceBuffer k = cl.allocate("bench keys", keys.size()), v = cl.allocate("bench values", n * 4ull);
  std::vector<double> wall;
  std::map<std::string, double> device;
  double cpu = 0;
  for (int rep = 0; rep <= reps; ++rep) {
    cl.write(k, 0, keys.size(), keys.data(), false);
    cl.write(v, 0, n * 4ull, values.data());
    std::map<std::string, double> seconds;
    const double cpu_start = cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    sort.sort(k, v, n, bits, &seconds);
    cl.finish();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (rep == 0) continue;  // warm-up
    cpu += (cpu_seconds() - cpu_start) / reps;
    wall.push_back(s);
    for (const auto& [name, t] : seconds) device[name] += t / reps;
  }
  std::sort(wall.begin(), wall.end());
  const double median = wall[wall.size() / 2];
  std::string split;
  for (const auto& [name, t] : device) split += fmt::format("  {} {:.2f} ms", name.substr(5), t * 1e3);
  std::printf("%-10s %7.1f Mpairs/s median %7.1f best %8.2f ms, cpu %8.2f ms, %u commands |%s\n", label.c_str(),
              n / median * 1e-6, n / wall.front() * 1e-6, median * 1e3, cpu * 1e3, RadixSort::commands(bits),
              split.c_str());
  std::fflush(stdout);
}

}  // namespace

TEST(RadixSortBench, DISABLED_Tilings) {
  const ClContext cl(select_device(std::getenv("COHORT_DEVICE") ? std::getenv("COHORT_DEVICE") : ""));
  const ProgramCache cache(ProgramCache::default_directory());
  const auto n = static_cast<std::uint32_t>(env_number("COHORT_SORT_COUNT", 1000000));
  const auto bits = static_cast<unsigned>(std::min<std::uint64_t>(env_number("COHORT_SORT_BITS", 32), 64));
  const SortKey key = bits <= 32 ? SortKey::bits32 : SortKey::bits64;
  const int reps = static_cast<int>(std::max<std::uint64_t>(env_number("COHORT_SORT_REPS", 5), 1));
  std::printf("%s: %u pairs, %u-bit keys, %d repetitions\n", cl.device.name.c_str(), n, bits, reps);

  const char* spec = std::getenv("COHORT_SORT_TILINGS");
  std::string list = spec ? spec : "";
  if (list.empty())
    list = "default,1x1024,1x4096,1x16384,64x15/local,128x15/local,256x7/local,256x9/local,256x13/local";
  std::stringstream tilings(list);
  for (std::string item; std::getline(tilings, item, ',');) {
    if (item == "default") {
      RadixSort chosen(cl, cache, n, key);
      bench(cl, chosen, "default", n, bits, reps);
      continue;
    }
    const auto x = item.find('x');
    if (x == std::string::npos) continue;
    const auto group = static_cast<std::uint32_t>(std::stoul(item.substr(0, x)));
    const auto items = static_cast<std::uint32_t>(std::stoul(item.substr(x + 1)));
    const bool local = item.find("/local") != std::string::npos;
    if (group > cl.device.max_work_group) continue;
    try {
      auto sort = RadixSortTestAccess::make(cl, cache, n, group, items, local, key);
      bench(cl, *sort, item, n, bits, reps);
    } catch (const std::exception& e) {
      std::printf("%-10s failed: %s\n", item.c_str(), e.what());
    }
  }
}
