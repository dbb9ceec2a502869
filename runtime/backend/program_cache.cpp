#include "runtime/backend/program_cache.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "runtime/util/atomic_file.h"
#include "runtime/util/hash.h"

namespace cohort {
namespace {

// Entry layout: magic, key length, key, payload length, payload checksum, payload.
constexpr std::string_view kMagic = "COHORT-KERNEL-CACHE-1\n";

void append_u64(std::string& out, std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), 8); }

bool read_u64(std::string_view& in, std::uint64_t& v) {
  if (in.size() < 8) return false;
  std::memcpy(&v, in.data(), 8);
  in.remove_prefix(8);
  return true;
}

// The cached binary for `key`, or nothing when the entry is absent, truncated or does not match.
std::optional<std::string> read_entry(const std::filesystem::path& file, const std::string& key) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string_view view(data);
  if (!view.starts_with(kMagic)) return std::nullopt;
  view.remove_prefix(kMagic.size());
  std::uint64_t key_size = 0, payload_size = 0, checksum = 0;
  if (!read_u64(view, key_size) || view.size() < key_size || view.substr(0, key_size) != key) return std::nullopt;
  view.remove_prefix(key_size);
  if (!read_u64(view, payload_size) || !read_u64(view, checksum) || view.size() != payload_size) return std::nullopt;
  if (fnv1a64(view) != checksum) return std::nullopt;
  return std::string(view);
}

std::string make_entry(const std::string& key, const std::string& binary) {
  std::string out(kMagic);
  append_u64(out, key.size());
  out += key;
  append_u64(out, binary.size());
  append_u64(out, fnv1a64(binary));
  out += binary;
  return out;
}

}  // namespace

ProgramCache::ProgramCache(std::optional<std::filesystem::path> directory) : directory_(std::move(directory)) {}

std::filesystem::path ProgramCache::default_directory() {
  if (const char* dir = std::getenv("COHORT_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "cohort/kernels";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache/cohort/kernels";
  return std::filesystem::temp_directory_path() / "cohort-kernels";
}

std::string ProgramCache::key(const DeviceInfo& device, const std::string& source, const std::string& options) {
  return fmt::format("platform={}\ndevice={}\nversion={}\ndriver={}\noptions={}\nsource={:016x}/{}\n",
                     device.platform_name, device.name, device.version, device.driver_version, options,
                     fnv1a64(source), source.size());
}

std::optional<std::filesystem::path> ProgramCache::entry_file(const std::string& key) const {
  if (!directory_) return std::nullopt;
  return *directory_ / fmt::format("{:016x}.bin", fnv1a64(key));
}

std::optional<std::string> ProgramCache::load(const std::string& key) const {
  const auto file = entry_file(key);
  return file ? read_entry(*file, key) : std::nullopt;
}

void ProgramCache::store(const std::string& key, const std::string& binary) const {
  const auto file = entry_file(key);
  if (!file) return;
  try {
    std::filesystem::create_directories(*directory_);
    write_file_atomically(*file, make_entry(key, binary));
  } catch (const std::exception&) {
  }
}

}  // namespace cohort
