// One image's sample passes: hands them out in schedule order (to the devices of this process
// and, under MPI, to other ranks), and adds the partial films in pass order as they come back,
// whatever order they finish in. Stopping (sample count, --time, interrupt) only ends the hand-out,
// so every pass handed out is combined and the film always ends at a pass boundary.
#pragma once

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <map>
#include <mutex>

#include "runtime/render/run/adaptive.h"
#include "runtime/render/run/pass_source.h"
#include "runtime/render/renderer.h"

namespace cohort {

class PassJob final : public PassSource {
 public:
  // window: passes that may be handed out but not yet combined (bounds the partial films held).
  // devices: the hand-out starts once this many devices of this process are ready, so they start
  // together and the render clock (and --time) measures rendering, not compiling.
  PassJob(const RenderSettings& settings, const ProgressCallback& progress, const RenderControl& control,
          std::size_t window, std::size_t devices);

  void device_ready() override;
  std::optional<SamplePass> next() override;  // blocks while the window is full
  void deliver(PassFilm film) override;

  // The same hand-out without blocking, for passes that go to other MPI ranks.
  enum class Offer { pass, wait, end };
  Offer try_next(SamplePass& pass);

  void abort() override;
  const FilmState* device_keeps_image(std::function<std::vector<co_float4>()> read_image) override;
  void deliver_image(std::vector<co_float4> sums) override;
  // Partial films come back to the host even with one device here (other MPI ranks render too).
  void combine_on_host() { combine_on_host_ = true; }
  bool aborted() const;
  bool finished() const;  // nothing more will be handed out and everything handed out is combined
  FilmState finish();     // waits until finished (after next() said no more), saves the final checkpoint
  // finish(), then the image and the job's figures (samples, time, interruption) into `result`;
  // returns the film
  FilmState finish_into(RenderResult& result);

  // The image's mean radiance and its standard error from the spread of the passes' means (batch
  // means): the yardstick for renders that cannot agree bit for bit (different kinds of device).
  struct ImageMean {
    std::array<double, 3> mean{}, standard_error{};
  };
  ImageMean image_mean() const;  // over the passes of this run (not those of a resumed checkpoint)

  std::uint32_t resumed_samples() const { return resumed_samples_; }
  bool interrupted() const;
  std::uint64_t rays() const;
  // The render loop's wall time: from the first pass handed out to the last pass added to the
  // image (not the devices' teardown after it), or to now while passes are still out.
  double seconds() const;

 private:
  Offer offer(SamplePass& pass);  // with mutex_ held
  // Adaptive sampling: the pixels of the round `pass` belongs to, chosen once per round from the
  // film at its start (adaptive.h); false while earlier passes are still out. With mutex_ held.
  bool choose_round_pixels(const SamplePass& pass);
  void combine(const PassFilm& film);
  double seconds_since_start() const;  // with mutex_ held

  using Clock = std::chrono::steady_clock;
  const RenderSettings settings_;
  const ProgressCallback progress_;
  const RenderControl control_;
  const PassSchedule schedule_;
  const std::size_t window_;
  const std::size_t devices_;
  std::uint32_t resumed_samples_ = 0;

  mutable std::mutex mutex_;
  std::optional<Clock::time_point> start_;
  std::optional<Clock::time_point> last_combined_;
  std::condition_variable changed_;
  FilmState film_;
  std::map<std::uint32_t, PassFilm> waiting_;  // finished passes that wait for an earlier one
  std::size_t ready_ = 0;                      // devices ready to render
  std::uint32_t handed_out_ = 0;               // passes [0, handed_out_) are handed out
  std::uint32_t combined_ = 0;                 // passes [0, combined_) are in film_
  bool ended_ = false;
  bool aborted_ = false;
  bool interrupted_ = false;
  std::uint64_t rays_ = 0;
  bool combine_on_host_ = false;
  bool image_on_device_ = false;       // the one device keeps film_.sums (device_keeps_image)
  std::function<std::vector<co_float4>()> read_image_;
  std::vector<std::array<double, 4>> pass_means_;  // per combined pass: mean r, g, b and its samples
  double last_checkpoint_ = 0;
  // adaptive sampling: the current round's pixels, and those of each pass handed out, not yet combined
  PixelList round_pixels_;
  std::map<std::uint32_t, PixelList> handed_out_pixels_;
  std::uint32_t round_start_ = 0;
  bool round_chosen_ = false;
};

// The mean radiance per pixel of a film.
Image film_image(const FilmState& film);

// The window for `devices` devices in all and films of `film_bytes`: enough to keep every device
// busy while one is late, at most ~2 GiB of waiting films unless that leaves a device idle.
std::size_t pass_window(std::size_t devices, std::size_t film_bytes);

}  // namespace cohort
