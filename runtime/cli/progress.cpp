#include "runtime/cli/progress.h"

#include <unistd.h>

#include <string>

#include <fmt/format.h>

namespace cohort {

ProgressReporter::ProgressReporter(std::FILE* out) : out_(out), terminal_(::isatty(::fileno(out)) != 0) {}

void ProgressReporter::update(const Progress& p) {
  const double mrays = p.seconds > 0 ? static_cast<double>(p.rays) / p.seconds * 1e-6 : 0;
  const double fraction = p.samples_target ? static_cast<double>(p.samples_done) / p.samples_target : 0;
  const double left = fraction > 0 ? p.seconds * (1 - fraction) / fraction : 0;
  const std::string target = p.samples_target ? fmt::format("/{}", p.samples_target) : "";
  if (terminal_) {
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    fmt::print(out_, "\r[{}{}] {}{} spp  {:.1f} Mrays/s  {:.1f}s left ", std::string(filled, '#'),
               std::string(width - filled, ' '), p.samples_done, target, mrays, left);
    std::fflush(out_);
    drawn_ = true;
    return;
  }
  // plain lines at most every 5 s, and always for the last pass
  if (p.seconds - last_line_ < 5 && p.samples_done != p.samples_target) return;
  last_line_ = p.seconds;
  fmt::print(out_, "progress: {}{} spp, {:.1f} Mrays/s, {:.1f}s elapsed, {:.1f}s left\n", p.samples_done, target,
             mrays, p.seconds, left);
}

void ProgressReporter::finish() {
  if (terminal_ && drawn_) fmt::print(out_, "\n");
}

}  // namespace cohort
