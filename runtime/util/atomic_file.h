// Writes a file so that readers see either the old file or the whole new one, never a part.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>

namespace cohort {

// Calls write(temp_path) to produce the file under a temporary name in the same directory, then
// renames it over `path`. On any exception the temporary file is removed and `path` is untouched.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write);

// Convenience for bytes already in memory.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace cohort
