// The canonical split of a render into sample passes. The film is the sum, in pass order, of one
// partial film per pass (each a per-pixel sum in sample order, started from zero), so whoever
// renders a pass (this device, another device, another MPI rank) the image has the same bits. The
// pass size therefore depends on the image size and sample count only, never on the device, the
// method or how many devices share the work.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace cohort {

struct SamplePass {
  std::uint32_t index = 0;         // position in the schedule: partial films are added in this order
  std::uint32_t first_sample = 0;  // samples [first_sample, first_sample + samples) of every pixel
  std::uint32_t samples = 0;
  // adaptive sampling (adaptive.h): the pixels the pass renders, ascending; null: every pixel
  std::shared_ptr<const std::vector<std::uint32_t>> pixels;
};

// Passes of 1-4 M samples: 16 passes when that keeps each above ~1 M samples and 64 samples a
// pixel (load balance over devices and ranks), never more than ~4 M samples (a wavefront launch's
// result buffer), at least one sample per pixel. Why 64 samples a pixel where 4 M allow it: a CPU
// work item traces its pixel's samples of a pass one after the other, and a pass of 16 against one
// of 64 cost 5-12 % of a 256x256 render on PoCL (the per-pixel set-up and the walks' cache reuse;
// docs/design.md, "Film"). spp 0 (a time limit ends the render): ~256 K samples, so the limit is
// not overshot by much.
std::uint32_t default_pass_samples(std::uint32_t width, std::uint32_t height, std::uint32_t spp);

class PassSchedule {
 public:
  // spp 0: unbounded (a time limit ends the render). `rounds`: adaptive sampling, whose passes also
  // end at every round's end (adaptive.h), so each round is a whole number of passes.
  PassSchedule(std::uint32_t pass_samples, std::uint32_t first_sample, std::uint32_t spp, bool rounds = false);

  std::optional<SamplePass> pass(std::uint32_t index) const;  // nullopt past the last pass
  std::uint32_t pass_samples() const { return pass_samples_; }
  std::uint32_t first_sample() const { return first_sample_; }

 private:
  std::uint32_t pass_samples_;
  std::uint32_t first_sample_;
  std::uint32_t spp_;
  bool rounds_;
};

}  // namespace cohort
