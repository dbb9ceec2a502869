// Saved render progress: the film sums, the samples done and a fingerprint of what was rendered,
// so `--resume` continues exactly where a run stopped (the film is a per-pixel sum in sample
// order, so a resumed render equals an uninterrupted one bit for bit).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "kernels/common/types.h"

namespace cohort {

struct FilmState {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t samples = 0;
  std::uint64_t dropped_samples = 0;
  std::vector<co_float4> sums;  // width * height
};

// Written atomically: a crash while saving leaves the previous checkpoint.
void save_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, const FilmState& film);

// nullopt when there is no file; InputError when it is damaged or belongs to another render.
std::optional<FilmState> load_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint);

}  // namespace cohort
