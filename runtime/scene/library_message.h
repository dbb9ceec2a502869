// Turns a third-party loader's error text into one line fit for an InputError message.
#pragma once

#include <string>

namespace cohort {

// The first line, cut short: tinygltf quotes whole data URIs (megabytes) in its errors.
inline std::string library_message(const std::string& text) {
  constexpr std::size_t kMaxLength = 240;
  std::string line = text.substr(0, text.find('\n'));
  if (line.empty()) return "unknown error";
  if (line.size() > kMaxLength) line = line.substr(0, kMaxLength) + "...";
  return line;
}

}  // namespace cohort
