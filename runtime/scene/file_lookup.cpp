#include "runtime/scene/file_lookup.h"

#include <algorithm>
#include <cctype>

namespace cohort {
namespace {

bool same_ignoring_case(const std::string& a, const std::string& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(),
                    [](unsigned char x, unsigned char y) { return std::tolower(x) == std::tolower(y); });
}

std::optional<std::filesystem::path> find_entry(const std::filesystem::path& dir, const std::string& part) {
  std::error_code ec;
  if (std::filesystem::exists(dir / part, ec)) return dir / part;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (same_ignoring_case(it->path().filename().string(), part)) return it->path();
  return std::nullopt;
}

}  // namespace

std::optional<std::filesystem::path> find_file(const std::filesystem::path& dir, const std::string& name) {
  std::string normal = name;
  std::replace(normal.begin(), normal.end(), '\\', '/');
  const std::filesystem::path relative(normal);
  std::error_code ec;
  if (std::filesystem::is_regular_file(dir / relative, ec)) return dir / relative;
  std::filesystem::path at = relative.is_absolute() ? relative.root_path() : dir;
  for (const auto& part : relative.relative_path()) {
    const auto next = find_entry(at, part.string());
    if (!next) return std::nullopt;
    at = *next;
  }
  if (!std::filesystem::is_regular_file(at, ec)) return std::nullopt;
  return at;
}

}  // namespace cohort
