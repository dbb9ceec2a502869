#include "fuzz_targets.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include <zlib.h>

#include "runtime/scene/gzip_file.h"
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

// gzip of `payload` in one member (the deflate level varies the stream's block layout).
std::string gzip_member(std::string_view payload, int level) {
  z_stream z{};
  if (deflateInit2(&z, level, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("deflateInit2 failed");
  std::string out(deflateBound(&z, static_cast<uLong>(payload.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(payload.data()));
  z.avail_in = static_cast<uInt>(payload.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (rc != Z_STREAM_END) throw std::runtime_error("deflate did not finish");
  return out;
}

void write_bytes(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

void gzip_round_trip(const std::uint8_t* data, std::size_t size) {
  if (size < 4) return;
  enum Mutation { intact, cut, flip, two_members };
  const auto mutation = static_cast<Mutation>(data[0] % 4);
  const std::size_t position = data[1] | std::size_t{data[2]} << 8;
  const auto mask = static_cast<char>(data[3] | 1);
  const std::string_view payload(reinterpret_cast<const char*>(data + 4), size - 4);
  const int level = data[0] / 4 % 10;
  std::string file;
  if (mutation == two_members) {
    const std::size_t split = payload.empty() ? 0 : position % payload.size();
    file = gzip_member(payload.substr(0, split), level) + gzip_member(payload.substr(split), level);
  } else {
    file = gzip_member(payload, level);
  }
  if (mutation == cut) file.resize(position % file.size());
  if (mutation == flip) file[position % file.size()] ^= mask;

  const ScratchDir scratch;
  const fs::path path = scratch.path() / "input.bin.gz";
  write_bytes(path, file);
  try {
    const std::string read = read_whole_file(path);
    if (mutation == cut) throw std::logic_error("a gzip file cut short was read without an error");
    if (read != payload) throw std::logic_error("a gzip file read without an error differs from what was written");
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (mutation == intact || mutation == two_members)
      throw std::logic_error("an intact gzip file was rejected: " + message);
    if (message.find(path.string()) == std::string::npos ||
        (message.find("truncated") == std::string::npos && message.find("corrupt") == std::string::npos))
      throw std::logic_error("gzip error that does not name the file and say truncated or corrupt: " + message);
  }
}

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
  write_bytes(path, std::string_view(reinterpret_cast<const char*>(data), size));
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
