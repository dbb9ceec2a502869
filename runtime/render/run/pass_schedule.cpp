#include "runtime/render/run/pass_schedule.h"

#include <algorithm>

#include "runtime/render/run/adaptive.h"

namespace cohort {

std::uint32_t default_pass_samples(std::uint32_t width, std::uint32_t height, std::uint32_t spp) {
  constexpr std::uint64_t kFullLaunch = 1u << 20, kMostPerPass = 1u << 22, kTimed = 1u << 18;
  constexpr std::uint32_t kPasses = 16, kPixelRun = 64;
  const std::uint64_t pixels = std::max<std::uint64_t>(std::uint64_t(width) * height, 1);
  const auto most = static_cast<std::uint32_t>(std::max<std::uint64_t>(kMostPerPass / pixels, 1));
  const auto full = static_cast<std::uint32_t>(std::max<std::uint64_t>((kFullLaunch + pixels - 1) / pixels, 1));
  const std::uint32_t least = std::min(std::max(full, kPixelRun), most);
  if (spp == 0) return static_cast<std::uint32_t>(std::max<std::uint64_t>(kTimed / pixels, 1));
  return std::clamp((spp + kPasses - 1) / kPasses, least, most);
}

PassSchedule::PassSchedule(std::uint32_t pass_samples, std::uint32_t first_sample, std::uint32_t spp, bool rounds)
    : pass_samples_(std::max(pass_samples, 1u)), first_sample_(first_sample), spp_(spp), rounds_(rounds) {}

std::optional<SamplePass> PassSchedule::pass(std::uint32_t index) const {
  const std::uint64_t end = spp_ ? spp_ : std::uint64_t(UINT32_MAX);
  if (!rounds_) {
    const std::uint64_t first = first_sample_ + std::uint64_t(index) * pass_samples_;
    if (first >= end) return std::nullopt;
    const auto samples = static_cast<std::uint32_t>(std::min<std::uint64_t>(pass_samples_, end - first));
    return SamplePass{index, static_cast<std::uint32_t>(first), samples, nullptr};
  }
  // passes of pass_samples_ from the start of each round (or from a resumed film's samples, a pass
  // boundary of the same schedule), the last one of a round cut at its end
  std::uint64_t start = first_sample_, skipped = 0;
  while (start < end) {
    const std::uint64_t round_end_sample = round_end(static_cast<std::uint32_t>(start), spp_);
    const std::uint64_t passes = (round_end_sample - start + pass_samples_ - 1) / pass_samples_;
    if (index < skipped + passes) {
      const std::uint64_t first = start + (index - skipped) * pass_samples_;
      const auto samples = static_cast<std::uint32_t>(std::min<std::uint64_t>(pass_samples_, round_end_sample - first));
      return SamplePass{index, static_cast<std::uint32_t>(first), samples, nullptr};
    }
    skipped += passes;
    start = round_end_sample;
  }
  return std::nullopt;
}

}  // namespace cohort
