// libFuzzer target: bytes loaded as a .ply.gz file (inflated, then read as PLY), and the same bytes
// as a payload that must come back whole or not at all (gzip_round_trip). Built by scripts/fuzz.
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cohort::fuzz::load_bytes(cohort::fuzz::targets()[4], data, size);
  cohort::fuzz::gzip_round_trip(data, size);
  return 0;
}
