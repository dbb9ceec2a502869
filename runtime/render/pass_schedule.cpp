#include "runtime/render/pass_schedule.h"

#include <algorithm>

namespace cohort {

std::uint32_t default_pass_samples(std::uint32_t width, std::uint32_t height, std::uint32_t spp) {
  constexpr std::uint64_t kFullLaunch = 1u << 20, kMostPerPass = 1u << 22, kTimed = 1u << 18;
  constexpr std::uint32_t kPasses = 16;
  const std::uint64_t pixels = std::max<std::uint64_t>(std::uint64_t(width) * height, 1);
  const auto least = static_cast<std::uint32_t>(std::max<std::uint64_t>((kFullLaunch + pixels - 1) / pixels, 1));
  const auto most = static_cast<std::uint32_t>(std::max<std::uint64_t>(kMostPerPass / pixels, 1));
  if (spp == 0) return static_cast<std::uint32_t>(std::max<std::uint64_t>(kTimed / pixels, 1));
  return std::clamp((spp + kPasses - 1) / kPasses, std::min(least, most), most);
}

PassSchedule::PassSchedule(std::uint32_t pass_samples, std::uint32_t first_sample, std::uint32_t spp)
    : pass_samples_(std::max(pass_samples, 1u)), first_sample_(first_sample), spp_(spp) {}

std::optional<SamplePass> PassSchedule::pass(std::uint32_t index) const {
  const std::uint64_t first = first_sample_ + std::uint64_t(index) * pass_samples_;
  const std::uint64_t end = spp_ ? spp_ : std::uint64_t(UINT32_MAX);
  if (first >= end) return std::nullopt;
  const auto samples = static_cast<std::uint32_t>(std::min<std::uint64_t>(pass_samples_, end - first));
  return SamplePass{index, static_cast<std::uint32_t>(first), samples};
}

}  // namespace cohort
