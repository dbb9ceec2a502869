#include "runtime/backend/embedded_sources.h"

#include <set>
#include <sstream>
#include <stdexcept>

namespace cohort {
namespace {

const EmbeddedSource* find_source(std::string_view path, const std::vector<EmbeddedSource>& first) {
  for (const auto* table : {&first, &embedded_sources()})
    for (const auto& s : *table)
      if (path == s.path) return &s;
  return nullptr;
}

void expand(std::string_view path, const std::vector<EmbeddedSource>& first, std::set<std::string>& seen,
            std::string& out) {
  if (!seen.insert(std::string(path)).second) return;  // each file once; the guards agree
  const EmbeddedSource* src = find_source(path, first);
  if (!src) throw std::runtime_error("kernel source not embedded: " + std::string(path));
  std::istringstream in(src->text);
  std::string line;
  int number = 0;
  out += "#line 1 \"" + std::string(path) + "\"\n";
  while (std::getline(in, line)) {
    ++number;
    const auto pos = line.find("#include \"");
    if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
      const auto start = pos + 10;
      const auto end = line.find('"', start);
      expand(line.substr(start, end - start), first, seen, out);
      out += "#line " + std::to_string(number + 1) + " \"" + std::string(path) + "\"\n";
      continue;
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string expand_kernel_source(std::string_view path, const std::vector<EmbeddedSource>& first) {
  std::set<std::string> seen;
  std::string out;
  expand(path, first, seen, out);
  return out;
}

}  // namespace cohort
