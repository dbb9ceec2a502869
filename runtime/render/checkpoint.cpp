#include "runtime/render/checkpoint.h"

#include <cstring>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"
#include "runtime/util/hash.h"

namespace cohort {
namespace {

constexpr std::string_view kMagic = "COHORT-CHECKPOINT-2\n";
constexpr std::string_view kMagicV1 = "COHORT-CHECKPOINT-1\n";

struct Header {
  std::uint64_t fingerprint;
  std::uint32_t width, height, samples, pass_samples;
  std::uint64_t dropped;
  std::uint64_t checksum;  // of the film sums
};

}  // namespace

void save_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, const FilmState& film) {
  const std::string_view sums(reinterpret_cast<const char*>(film.sums.data()), film.sums.size() * sizeof(co_float4));
  const Header h{fingerprint, film.width, film.height, film.samples, film.pass_samples, film.dropped_samples, fnv1a64(sums)};
  std::string bytes(kMagic);
  bytes.append(reinterpret_cast<const char*>(&h), sizeof(h));
  bytes.append(sums);
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
  if (data.size() < kMagic.size() + sizeof(h) || data.compare(0, kMagic.size(), kMagic) != 0)
    throw InputError(fmt::format("{}: not a Cohort checkpoint", path.string()));
  std::memcpy(&h, data.data() + kMagic.size(), sizeof(h));
  if (h.fingerprint != fingerprint)
    throw InputError(fmt::format("{}: the checkpoint belongs to another scene or other settings (resolution, seed, "
                                 "depth, lights); remove it or render to another -o",
                                 path.string()));
  const std::size_t film_bytes = std::size_t(h.width) * h.height * sizeof(co_float4);
  const std::string_view sums(data.data() + kMagic.size() + sizeof(h), data.size() - kMagic.size() - sizeof(h));
  if (sums.size() != film_bytes || fnv1a64(sums) != h.checksum || h.pass_samples == 0)
    throw InputError(fmt::format("{}: the checkpoint is damaged (size or checksum)", path.string()));
  FilmState film;
  film.width = h.width;
  film.height = h.height;
  film.samples = h.samples;
  film.pass_samples = h.pass_samples;
  film.dropped_samples = h.dropped;
  film.sums.resize(std::size_t(h.width) * h.height);
  std::memcpy(film.sums.data(), sums.data(), film_bytes);
  return film;
}

}  // namespace cohort
