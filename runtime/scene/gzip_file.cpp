#include "runtime/scene/gzip_file.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>

#include <fmt/format.h>
#include <zlib.h>

#include "runtime/util/error.h"

namespace cohort {
namespace {

// tinygltf takes 32-bit lengths and no model we load comes near this, so a larger result is a
// decompression bomb or corruption rather than a scene.
constexpr std::uint64_t kMaxInflatedBytes = std::uint64_t{4} << 30;

std::string read_raw(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(fmt::format("{}: no such file", path.string()));
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("{}: not a regular file", path.string()));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the file", path.string()));
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(fmt::format("{}: cannot read the file size", path.string()));
  std::string bytes(size, '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw InputError(fmt::format("{}: read failed", path.string()));
  return bytes;
}

// Caps one zlib call's byte counts at what its 32-bit fields hold.
uInt chunk(std::size_t bytes) { return static_cast<uInt>(std::min<std::size_t>(bytes, 1u << 30)); }

// RAII owner of a zlib inflate stream.
class Inflater {
 public:
  explicit Inflater(const std::filesystem::path& path) : path_(path) {
    // 16 + MAX_WBITS: expect a gzip header and trailer, not a raw zlib stream.
    if (inflateInit2(&stream_, 16 + MAX_WBITS) != Z_OK)
      throw InputError(fmt::format("{}: zlib could not start", path_.string()));
  }
  ~Inflater() { inflateEnd(&stream_); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  std::string inflate_all(const std::string& in) {
    std::string out(std::max<std::size_t>(4 * in.size(), 1 << 16), '\0');
    std::size_t in_at = 0, out_at = 0;
    for (;;) {
      if (out_at == out.size()) grow(out);
      const int rc = step(in, in_at, out, out_at);
      if (rc == Z_STREAM_END) {
        // gzip allows several members back to back; zero padding after the last one is common.
        if (!more_members(in, in_at)) break;
        inflateReset(&stream_);
      } else if (rc == Z_BUF_ERROR && in_at == in.size()) {
        throw InputError(fmt::format("{}: truncated gzip data", path_.string()));
      } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
        throw InputError(fmt::format("{}: corrupt gzip data ({})", path_.string(),
                                     stream_.msg ? stream_.msg : "zlib error"));
      }
    }
    out.resize(out_at);
    return out;
  }

 private:
  int step(const std::string& in, std::size_t& in_at, std::string& out, std::size_t& out_at) {
    stream_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + in_at));
    stream_.avail_in = chunk(in.size() - in_at);
    stream_.next_out = reinterpret_cast<Bytef*>(out.data() + out_at);
    stream_.avail_out = chunk(out.size() - out_at);
    const uInt in_before = stream_.avail_in, out_before = stream_.avail_out;
    const int rc = inflate(&stream_, Z_NO_FLUSH);
    in_at += in_before - stream_.avail_in;
    out_at += out_before - stream_.avail_out;
    return rc;
  }

  void grow(std::string& out) const {
    if (out.size() >= kMaxInflatedBytes)
      throw InputError(
          fmt::format("{}: inflates to more than {} GiB", path_.string(), kMaxInflatedBytes >> 30));
    out.resize(std::min<std::uint64_t>(2 * out.size(), kMaxInflatedBytes));
  }

  static bool more_members(const std::string& in, std::size_t at) {
    return std::any_of(in.begin() + static_cast<std::ptrdiff_t>(at), in.end(),
                       [](char c) { return c != '\0'; });
  }

  const std::filesystem::path& path_;
  z_stream stream_{};
};

}  // namespace

bool is_gzip_name(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gz";
}

std::string read_whole_file(const std::filesystem::path& path) {
  std::string bytes = read_raw(path);
  if (!is_gzip_name(path)) return bytes;
  return Inflater(path).inflate_all(bytes);
}

}  // namespace cohort
