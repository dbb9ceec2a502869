#include "fuzz_targets.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "runtime/scene/scene.h"
#include "runtime/util/error.h"

namespace cohort::fuzz {
namespace {

namespace fs = std::filesystem;

// A fresh directory per input, removed after it (libFuzzer may leave without running destructors):
// loaders resolve relative references (buffers, textures, .mtl files) against it, so it holds nothing
// but the current input. A crash leaves it behind with the input in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "cohort-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"gltf", ".gltf"}, {"glb", ".glb"}, {"obj", ".obj"}, {"ply", ".ply"}, {"gzip", ".ply.gz"}};
  return all;
}

void load_file(const fs::path& path) {
  try {
    const Scene scene = load_scene(path);
    (void)scene.bounds();
  } catch (const InputError&) {
    // the expected outcome of bad input
  }
}

void load_bytes(const Target& target, const std::uint8_t* data, std::size_t size) {
  const ScratchDir scratch;
  const fs::path path = scratch.path() / (std::string("input") + target.extension);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) throw std::runtime_error("cannot write " + path.string());
  }
  load_file(path);
}

const Target* target_for_file(const fs::path& path) {
  const std::string name = lower(path.filename().string());
  const auto ends_with = [&](const std::string& suffix) {
    return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with(".gz")) return &targets()[4];
  for (std::size_t i = 0; i < 4; ++i)
    if (ends_with(targets()[i].extension)) return &targets()[i];
  return nullptr;
}

}  // namespace cohort::fuzz
