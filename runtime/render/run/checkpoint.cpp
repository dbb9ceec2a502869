#include "runtime/render/run/checkpoint.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"
#include "runtime/util/hash.h"

namespace cohort {
namespace {

constexpr std::string_view kMagic = "COHORT-CHECKPOINT-3\n";
constexpr std::string_view kMagicV2 = "COHORT-CHECKPOINT-2\n";
constexpr std::string_view kMagicV1 = "COHORT-CHECKPOINT-1\n";

struct Header {
  std::uint64_t fingerprint;
  std::uint32_t width, height, samples, pass_samples;
  std::uint64_t dropped;
  std::uint64_t checksum;  // of the film sums, and (version 3) of the per-pixel counts after them
};

// Version 3 only, after the header: how many per-pixel counts follow the sums (0 or every pixel).
struct CountsHeader {
  std::uint64_t pixel_counts;
};

}  // namespace

void save_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, const FilmState& film) {
  const std::string_view sums(reinterpret_cast<const char*>(film.sums.data()), film.sums.size() * sizeof(co_float4));
  const std::string_view counts(reinterpret_cast<const char*>(film.pixel_samples.data()),
                                film.pixel_samples.size() * sizeof(std::uint32_t));
  std::string payload(sums);
  payload.append(counts);
  const Header h{fingerprint, film.width, film.height, film.samples, film.pass_samples, film.dropped_samples,
                 fnv1a64(payload)};
  const CountsHeader c{film.pixel_samples.size()};
  std::string bytes(kMagic);
  bytes.append(reinterpret_cast<const char*>(&h), sizeof(h));
  bytes.append(reinterpret_cast<const char*>(&c), sizeof(c));
  bytes.append(payload);
  write_file_atomically(path, bytes);
}

std::optional<FilmState> load_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Header h{};
  if (data.compare(0, kMagicV1.size(), kMagicV1) == 0)
    throw InputError(fmt::format("{}: a checkpoint of an older Cohort (version 1, one running sum) cannot continue "
                                 "a pass-ordered film; remove it or render to another -o",
                                 path.string()));
  const bool v2 = data.compare(0, kMagicV2.size(), kMagicV2) == 0;
  const std::size_t header_bytes = kMagic.size() + sizeof(h) + (v2 ? 0 : sizeof(CountsHeader));
  if (data.size() < header_bytes || !(v2 || data.compare(0, kMagic.size(), kMagic) == 0))
    throw InputError(fmt::format("{}: not a Cohort checkpoint", path.string()));
  std::memcpy(&h, data.data() + kMagic.size(), sizeof(h));
  CountsHeader c{0};
  if (!v2) std::memcpy(&c, data.data() + kMagic.size() + sizeof(h), sizeof(c));
  if (h.fingerprint != fingerprint)
    throw InputError(fmt::format("{}: the checkpoint belongs to another scene or other settings (resolution, seed, "
                                 "depth, lights, target error); remove it or render to another -o",
                                 path.string()));
  const std::size_t pixels = std::size_t(h.width) * h.height;
  const std::size_t film_bytes = pixels * sizeof(co_float4);
  const std::string_view payload(data.data() + header_bytes, data.size() - header_bytes);
  if ((c.pixel_counts != 0 && c.pixel_counts != pixels) ||
      payload.size() != film_bytes + c.pixel_counts * sizeof(std::uint32_t) || fnv1a64(payload) != h.checksum ||
      h.pass_samples == 0)
    throw InputError(fmt::format("{}: the checkpoint is damaged (size or checksum)", path.string()));
  const std::string_view sums = payload.substr(0, film_bytes);
  FilmState film;
  film.width = h.width;
  film.height = h.height;
  film.samples = h.samples;
  film.pass_samples = h.pass_samples;
  film.dropped_samples = h.dropped;
  film.sums.resize(std::size_t(h.width) * h.height);
  std::memcpy(film.sums.data(), sums.data(), film_bytes);
  film.pixel_samples.resize(c.pixel_counts);
  // (no counts without --target-error: memcpy from or to a null pointer is undefined even for 0 bytes)
  if (c.pixel_counts)
    std::memcpy(film.pixel_samples.data(), payload.data() + film_bytes, c.pixel_counts * sizeof(std::uint32_t));
  return film;
}

}  // namespace cohort
