// Saved render progress: the film sums, the samples done and a fingerprint of what was rendered,
// so `--resume` continues exactly where a run stopped (the film is the pass-ordered sum of
// pass_schedule.h and stops at a pass boundary, so a resumed render equals an uninterrupted one bit
// for bit). Version 2 adds the pass size; version-1 films were one running sum and are refused.
// Version 3 adds each pixel's sample count (adaptive sampling); version 2 is still read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "kernels/common/core/types.h"

namespace cohort {

struct FilmState {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t samples = 0;
  std::uint32_t pass_samples = 0;  // the pass size of the schedule (pass_schedule.h) a resume continues
  std::uint64_t dropped_samples = 0;
  std::vector<co_float4> sums;  // width * height: the sum of the partial films of the passes, in pass order
                                // (rgb; w: the sum of the samples' squared luminance, adaptive.h)
  // adaptive sampling: the samples of each pixel (`samples` is the most); empty: every pixel has `samples`
  std::vector<std::uint32_t> pixel_samples;
};

// Written atomically: a crash while saving leaves the previous checkpoint.
void save_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint, const FilmState& film);

// nullopt when there is no file; InputError when it is damaged or belongs to another render.
std::optional<FilmState> load_checkpoint(const std::filesystem::path& path, std::uint64_t fingerprint);

}  // namespace cohort
