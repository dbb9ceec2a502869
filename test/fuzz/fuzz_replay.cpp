// Replays the kept fuzz corpus (test/fuzz/corpus/<target>/*) and the malformed-input corpus
// (test/data/bad-input/*) through the loader fuzz targets, with whatever compiler built it: CI runs
// this instead of fuzzing. Any exception other than cohort::InputError, a crash or a sanitizer
// report (in the sanitizer build) fails it, as does one input taking longer than kMaxSeconds.
//
//   fuzz_replay CORPUS_ROOT [EXTRA_DIR...]
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "fuzz_targets.h"

namespace fs = std::filesystem;
using cohort::fuzz::Target;

namespace {

constexpr double kMaxSeconds = 30.0;

struct Tally {
  int inputs = 0;
  int failures = 0;
  double slowest = 0.0;
  std::string slowest_name;
};

std::set<fs::path> files_in(const fs::path& dir) {
  std::set<fs::path> files;  // sorted, so runs are repeatable
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file()) files.insert(it->path());
  return files;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename F>
void replay(const std::string& name, Tally& tally, F&& load) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    load();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FAIL %s: %s\n", name.c_str(), e.what());
    ++tally.failures;
  } catch (...) {
    std::fprintf(stderr, "FAIL %s: unknown exception\n", name.c_str());
    ++tally.failures;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++tally.inputs;
  if (seconds > tally.slowest) {
    tally.slowest = seconds;
    tally.slowest_name = name;
  }
  if (seconds > kMaxSeconds) {
    std::fprintf(stderr, "FAIL %s: took %.1f s (limit %.0f s)\n", name.c_str(), seconds, kMaxSeconds);
    ++tally.failures;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuzz_replay CORPUS_ROOT [EXTRA_DIR...]\n");
    return 2;
  }
  Tally tally;
  // The kept corpus: each folder through its own target.
  const fs::path root = argv[1];
  for (const Target& target : cohort::fuzz::targets())
    for (const fs::path& file : files_in(root / target.name)) {
      const std::string bytes = read_file(file);
      replay(file.string(), tally, [&] {
        const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
        cohort::fuzz::load_bytes(target, data, bytes.size());
        if (std::string(target.name) == "gzip") cohort::fuzz::gzip_round_trip(data, bytes.size());
      });
    }
  // Other folders: each file a target reads (by its extension), loaded where it lies so that its
  // relative references (.mtl, buffers, textures) resolve.
  for (int i = 2; i < argc; ++i)
    for (const fs::path& file : files_in(argv[i]))
      if (cohort::fuzz::target_for_file(file)) replay(file.string(), tally, [&] { cohort::fuzz::load_file(file); });
  std::printf("fuzz_replay: %d inputs, %d failures; slowest %.3f s (%s)\n", tally.inputs, tally.failures,
              tally.slowest, tally.slowest_name.c_str());
  if (tally.inputs == 0) {
    std::fprintf(stderr, "fuzz_replay: no inputs found under %s\n", root.c_str());
    return 1;
  }
  return tally.failures == 0 ? 0 : 1;
}
