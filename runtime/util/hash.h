#pragma once

#include <cstdint>
#include <string_view>

namespace cohort {

// FNV-1a, 64-bit: a stable hash for cache keys and checksums (not for security).
constexpr std::uint64_t fnv1a64(std::string_view data, std::uint64_t h = 0xcbf29ce484222325ull) {
  for (unsigned char c : data) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace cohort
