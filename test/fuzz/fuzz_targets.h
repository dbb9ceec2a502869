// The loader fuzz targets, shared by the libFuzzer executables (fuzz_<target>.cpp) and by
// fuzz_replay, which runs the kept corpus and test/data/bad-input/ through them with any compiler.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace cohort::fuzz {

struct Target {
  const char* name;       // corpus folder under test/fuzz/corpus/
  const char* extension;  // the file name the bytes are loaded as ("input" + extension)
};

// gltf (.gltf text), glb (.glb), obj (.obj), ply (.ply), gzip (.ply.gz).
const std::vector<Target>& targets();

// Writes the bytes to a private temporary file named for the target and loads it with
// cohort::load_scene. InputError is the expected outcome of bad input; any other exception
// escapes (libFuzzer reports it as a crash, fuzz_replay as a failure).
void load_bytes(const Target& target, const std::uint8_t* data, std::size_t size);

// load_scene on an existing file, InputError caught.
void load_file(const std::filesystem::path& path);

// The gzip reader's contract, beyond "no crash": the bytes after four control bytes are gzipped
// (as one member, or two back to back), then optionally cut short or have one byte flipped, as the
// control bytes say. read_whole_file must return exactly the payload or throw InputError saying
// "truncated" or "corrupt"; a cut file must always fail. Throws std::logic_error when it does not.
void gzip_round_trip(const std::uint8_t* data, std::size_t size);

// The target a corpus file belongs to by its extension (looking through .gz), or nullptr.
const Target* target_for_file(const std::filesystem::path& path);

}  // namespace cohort::fuzz
