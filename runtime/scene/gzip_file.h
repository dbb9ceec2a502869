// Reads a whole file into memory, inflating it when its name ends in ".gz".
#pragma once

#include <filesystem>
#include <string>

namespace cohort {

// True when the file name ends in ".gz" (any letter case).
bool is_gzip_name(const std::filesystem::path& path);

// The file's bytes, inflated with zlib for a .gz name. Throws InputError naming the file when it
// cannot be read, is corrupt, or inflates past a sane limit.
std::string read_whole_file(const std::filesystem::path& path);

}  // namespace cohort
