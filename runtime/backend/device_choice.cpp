#include "runtime/backend/device_choice.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>

#include <fmt/format.h>

#include "runtime/util/error.h"

namespace cohort {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool name_matches(const DeviceInfo& d, const std::string& needle) {
  return lower(d.name).find(needle) != std::string::npos || lower(d.platform_name).find(needle) != std::string::npos;
}

// select_device's rule over `devices`, skipping those already `taken`.
DeviceInfo pick(const std::vector<DeviceInfo>& devices, const std::string& spec, const std::vector<bool>& taken) {
  if (spec.empty()) {
    for (const auto& d : devices)
      if (d.is_gpu) return d;
    for (const auto& d : devices)
      if (d.is_cpu) return d;
    return devices.front();
  }
  std::size_t index = 0;
  const auto [ptr, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), index);
  if (ec == std::errc() && ptr == spec.data() + spec.size()) {
    if (index < devices.size()) return devices[index];
    throw InputError(fmt::format("--device {}: there are only {} devices (see `cohort devices`)", spec,
                                 devices.size()));
  }
  const auto needle = lower(spec);
  for (const auto& d : devices)
    if (!taken[d.device_index] && name_matches(d, needle)) return d;
  throw InputError(fmt::format("--device {}: no {}device name matches (see `cohort devices`)", spec,
                               std::count(taken.begin(), taken.end(), true) ? "other " : ""));
}

// An empty --device means $COHORT_DEVICE when it is set.
std::string device_spec(const std::string& spec) {
  if (!spec.empty()) return spec;
  const char* env = std::getenv("COHORT_DEVICE");
  return env ? env : "";
}

}  // namespace

DeviceInfo select_device(const std::vector<DeviceInfo>& devices, const std::string& requested) {
  if (devices.empty()) throw InputError("no device found (see `cohort devices`)");
  const std::string spec = device_spec(requested);
  return pick(devices, spec, std::vector<bool>(devices.size(), false));
}

std::vector<DeviceInfo> select_devices(const std::vector<DeviceInfo>& devices, const std::string& requested,
                                       int local_rank) {
  if (devices.empty()) throw InputError("no device found (see `cohort devices`)");
  const std::string spec = device_spec(requested);
  if (spec == "all" || spec.starts_with("all:") || spec.starts_with("rank:")) {
    const std::size_t colon = spec.find(':');
    const std::string needle = lower(colon == std::string::npos ? "" : spec.substr(colon + 1));
    std::vector<DeviceInfo> chosen;
    for (const auto& d : devices)
      if (name_matches(d, needle)) chosen.push_back(d);
    if (chosen.empty()) throw InputError(fmt::format("--device {}: no device name matches (see `cohort devices`)", spec));
    if (spec.starts_with("rank:")) return {chosen[static_cast<std::size_t>(std::max(local_rank, 0)) % chosen.size()]};
    return chosen;
  }
  std::vector<bool> taken(devices.size(), false);
  std::vector<DeviceInfo> chosen;
  std::size_t start = 0;
  do {
    const std::size_t comma = spec.find(',', start);
    const std::string item = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty() && spec.find(',') != std::string::npos)
      throw InputError(fmt::format("--device {}: an empty item in the list", spec));
    DeviceInfo d = pick(devices, item, taken);
    if (taken[d.device_index]) throw InputError(fmt::format("--device {}: device {} is listed twice", spec, item));
    taken[d.device_index] = true;
    chosen.push_back(std::move(d));
    start = comma == std::string::npos ? std::string::npos : comma + 1;
  } while (start != std::string::npos);
  return chosen;
}

}  // namespace cohort
