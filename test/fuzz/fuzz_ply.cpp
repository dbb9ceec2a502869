// libFuzzer target: bytes loaded as a .ply file. Built by scripts/fuzz.
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cohort::fuzz::load_bytes(cohort::fuzz::targets()[3], data, size);
  return 0;
}
