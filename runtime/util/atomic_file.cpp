#include "runtime/util/atomic_file.h"

#include <unistd.h>

#include <random>
#include <fstream>
#include <stdexcept>
#include <string>

namespace cohort {

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  std::random_device entropy;  // distinct names for concurrent writers
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  // appended one by one: GCC 12 reports a false -Wrestrict on `"." + std::string&&`
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(entropy());
  const fs::path temp = dir / name;
  try {
    write(temp);
    fs::rename(temp, path);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  write_atomically(path, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write " + temp.string());
  });
}

}  // namespace cohort
