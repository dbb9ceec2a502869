// auto: the other methods take turns at the launches of the image's first passes, timed; the
// fastest renders the rest. Every method adds the same bits for the same samples (pass_driver.h:
// a launch's samples join the pass film in sample order, and a pixel's samples do not depend on
// which other pixels a launch holds), so the probe's launches are part of the image, not thrown
// away: the probe costs only the difference between the slower methods and the fastest on the
// samples each probed (docs/decisions.md: its time counts).
//
// Two rounds keep that difference small. The screen gives each method a quarter of a wave (the
// samples per pixel that fill the wavefront pool): enough to tell a method that is far behind,
// whose full wave would cost the most. The megakernel, first in the table, is screened on one
// sample of every 8th row where those rows are enough pixels (the next method renders the other
// rows of that sample): it keeps no pool, so a fraction of the image times it, and on a GPU its
// one-sample launch is the slowest of the screen (each work item's whole path: the launch waits
// for the longest). The final gives
// the (at most kFinalists) methods within kKeep of the screen's best one full wave each, the size
// at which sorting pays or does not, and picks the fastest there; the best sorting method within
// kKeep always gets a place (auto_finalists). All methods share one pool.
//
// The device's default method is the incumbent: it runs in the final whatever the screen said, timed
// first and last, and another method takes over only when it beats the default by more than the
// spread of the default's two timings (twice over, and by kMinMargin at least: auto_pick). The pick is
// then checked against its own cost: its rate over its first kCheckLaunches launches of the render,
// against the default's in the final; below kCheckKeep of it, the default renders the rest.
//
// A short render cannot pay for the probe: where the screen would take more than 1/kShortRender of
// the render's samples per pixel on a GPU, 1/kShortRenderCpu on a CPU, auto takes the device's
// default without probing (device_default_method: the method measured fastest on that kind of
// device). On a CPU the methods are further apart (sc+rg at 0.22-0.40x naive's rate on 2 cores), so
// each screened sample of a slow method costs two to four of the default's: the probe cost 3 % of
// the render with the screen at an eighth (256x256, 256 spp) and 2.6-3.7 % at a 64th (128x128,
// 1024 spp); at a 256th its share is about 1 %. On the H200 no method ever beat sc+rg by the
// margin (0.87-1.00x its rate on every scene measured, 2026-12-05), while the probe's launches took
// 0.09 s of a 64-spp render at 1024x1024 (0.27 s): a GPU probes where the screen takes at most a 32nd.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "runtime/backend/device_support.h"
#include "runtime/render/run/launch_log.h"
#include "runtime/render/methods/methods.h"
#include "runtime/render/methods/auto_finalists.h"
#include "runtime/render/stages/wavefront_loop.h"

namespace cohort {
namespace {

// Methods at least this fraction of the screen's best rate go on to the final round, at most
// kFinalists of them (the fastest of the screen).
constexpr double kKeep = 0.9;
constexpr std::size_t kFinalists = 3;
// The first method of the screen renders every kScreenRowStride-th row of one sample, where those
// rows hold at least kScreenRowsMinPixels pixels (fewer, and a launch's fixed costs would decide
// its rate: on 2 CPU cores a 2048-pixel screen timed the megakernel at 0.4-0.7x its rate).
constexpr std::uint32_t kScreenRowStride = 8;
constexpr std::uint32_t kScreenRowsMinPixels = 4096;
// The screen may take at most this fraction (its inverse) of the render's samples per pixel.
constexpr std::uint32_t kShortRender = 32;
constexpr std::uint32_t kShortRenderCpu = 256;
// A method other than the default must beat it by this much at least in the final (auto_pick).
constexpr double kMinMargin = 0.05;
// The pick's first launches after the final, and the share of the default's final rate they must keep.
constexpr std::uint32_t kCheckLaunches = 2;
constexpr double kCheckKeep = 0.97;

// The inverse of the largest share of the render's samples the screen may take: the device's rule,
// or COHORT_AUTO_PROBE_SHARE where set to a positive integer (for tests and experiments that need
// auto to probe a short render; docs/design.md).
std::uint32_t probe_share(bool is_gpu) {
  if (const char* v = std::getenv("COHORT_AUTO_PROBE_SHARE")) {
    char* end = nullptr;
    const unsigned long n = std::strtoul(v, &end, 10);
    if (end != v && *end == '\0' && n > 0 && n <= 1u << 20) return static_cast<std::uint32_t>(n);
  }
  return is_gpu ? kShortRender : kShortRenderCpu;
}

struct Candidate {
  const Method* method = nullptr;
  RenderSettings settings;  // the render's, named for the method (its launcher keeps a reference)
  std::unique_ptr<PassLauncher> launcher;
  double screen_rate = -1, final_rate = -1;  // rays per second; -1: not probed in that round
  double final_rate_again = -1;               // the default's second timing in the final
};

void add_output(PassOutput& total, PassOutput out, std::size_t straggler_rays) {
  total.rays += out.rays;
  add_seconds(total.kernel_seconds, out.kernel_seconds);
  total.max_steps = std::max(total.max_steps, out.max_steps);
  total.host_reads += out.host_reads;
  total.sort_launches += out.sort_launches;
  total.extension_steps.insert(total.extension_steps.end(), out.extension_steps.begin(), out.extension_steps.end());
  if (straggler_rays) keep_worst(total.worst_rays, std::move(out.worst_rays), straggler_rays);
}

class AutoMethod final : public PassLauncher {
 public:
  explicit AutoMethod(const MethodInputs& in) : device_(in.device), settings_(in.settings) {
    auto memory = std::make_shared<WavefrontMemory>(in.device, in.settings);
    pool_slots_ = memory->pool.slots;
    for (const Method& m : methods()) {
      if (m.set_up == auto_method) continue;
      if (m.sorts && !device_support(in.device.info()).sorts) continue;  // the device cannot sort
      if (m.sorts && (in.scene.bvh8 || in.scene.bvh8f)) continue;  // hash and pth do not walk the 8-wide BVHs
      auto c = std::make_unique<Candidate>();
      c->method = &m;
      c->settings = in.settings;
      c->settings.method = m.name;
      c->launcher = m.set_up(
          MethodInputs{in.device, in.cache, in.scene, in.params, c->settings, in.progress, in.control, memory});
      max_per_launch_ = std::min(max_per_launch_, c->launcher->max_samples_per_launch());
      queue_.push_back(c.get());
      candidates_.push_back(std::move(c));
    }
    // the first screen step's pixel lists: every 8th row, and the other rows
    std::vector<std::uint32_t> rows, rest;
    for (std::uint32_t y = 0; y < in.settings.height; ++y)
      for (std::uint32_t x = 0; x < in.settings.width; ++x)
        (y % kScreenRowStride == 0 ? rows : rest).push_back(y * in.settings.width + x);
    if (!rest.empty() && rows.size() >= kScreenRowsMinPixels && queue_.size() >= 2) {
      screen_rows_ = {device_.allocate("auto's screen rows", rows.size() * 4, rows.data(), Access::read_only),
                      static_cast<std::uint32_t>(rows.size())};
      other_rows_ = {device_.allocate("auto's other rows", rest.size() * 4, rest.data(), Access::read_only),
                     static_cast<std::uint32_t>(rest.size())};
    }
    const std::string fallback = device_default_method(in.device.info().is_gpu);
    for (const auto& c : candidates_)
      if (c->method->name == fallback) default_ = c.get();
    take_default_if_short(in);
  }

  std::uint32_t max_samples_per_launch() const override { return max_per_launch_; }
  // whole passes: the probe splits them into its own launches
  std::uint32_t first_launch_samples() const override { return max_per_launch_; }

  PassOutput launch(const PassBuffers& b, const RenderParams& p) override {
    PassOutput total;
    for (std::uint32_t done = 0; done < p.samples_per_pass;) {
      const std::uint32_t left = p.samples_per_pass - done;
      if (chosen_) {
        const auto start = std::chrono::steady_clock::now();
        PassOutput out = run(*chosen_, b, p, done, left);
        check_pick(out.rays, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        add_output(total, std::move(out), settings_.straggler_rays);
        break;
      }
      // the first screen step splits one sample by rows (not in adaptive passes: they list pixels)
      if (screening_ && !split_done_ && screen_rows_.pixels && p.active_pixels == 0) {
        split_done_ = true;
        // the second method takes the other rows first: the render's first launch pays the
        // one-time costs (first use of buffers and kernels), and the megakernel's small launch
        // would weigh them most
        std::swap(queue_[0], queue_[1]);
        for (const PixelRows* rows : {&other_rows_, &screen_rows_}) {
          PassBuffers subset = b;
          subset.pixel_list = rows->list;
          add_output(total, probe(subset, p, done, 1, rows->pixels), settings_.straggler_rays);
        }
        done += 1;
        continue;
      }
      const std::uint32_t samples = std::min(round_samples(p), left);
      add_output(total, probe(b, p, done, samples, p.active_pixels), settings_.straggler_rays);
      done += samples;
    }
    return total;
  }

  void report(RenderResult& result) const override {
    const Candidate* pick = chosen_ ? chosen_ : best(screening_);
    for (const auto& c : candidates_) {
      if (c.get() == pick) continue;
      RenderResult other;  // only the compile time of the methods not picked
      c->launcher->report(other);
      result.compile_seconds += other.compile_seconds;
    }
    if (!pick) return;
    pick->launcher->report(result);
    AutoChoice& a = result.auto_choice;
    a.method = pick->method->name;
    a.reason = reason_.empty() ? "the fastest of the probe" : reason_;
    a.screen_rows = split_done_ && screen_rows_.pixels;
    a.probe_seconds = probe_seconds_;
    for (const auto& c : candidates_) {
      if (c->screen_rate >= 0) a.probe_rays_per_second[c->method->name] = c->screen_rate;
      if (c->final_rate >= 0) a.final_rays_per_second[c->method->name] = std::max(c->final_rate, c->final_rate_again);
    }
  }

 private:
  // The screen's samples per pixel over the whole image against the render's: too many, and the
  // device's default renders it all.
  void take_default_if_short(const MethodInputs& in) {
    const std::uint32_t pixels = std::max<std::uint32_t>(in.settings.width * in.settings.height, 1);
    const std::uint32_t quarter_wave = std::max<std::uint32_t>(std::clamp<std::uint32_t>(pool_slots_ / pixels, 1, max_per_launch_) / 4, 1);
    const auto others = static_cast<std::uint32_t>(candidates_.size());
    const std::uint32_t screen = screen_rows_.pixels ? 1 + (others - 2) * quarter_wave : others * quarter_wave;
    const std::uint32_t short_render = probe_share(in.device.info().is_gpu);
    if (in.settings.spp == 0 || std::uint64_t(screen) * short_render <= in.settings.spp) return;
    chosen_ = default_;
    queue_.clear();
    reason_ = fmt::format("the default on a {}: the render ({} spp) is too short to probe (the screen takes {} spp)",
                          in.device.info().is_gpu ? "GPU" : "CPU", in.settings.spp, screen);
  }

  // Samples [done, done + samples) of the launch `p` by `c` (its own parameters when they differ).
  PassOutput run(Candidate& c, const PassBuffers& b, const RenderParams& p, std::uint32_t done, std::uint32_t samples,
                 std::uint32_t active_pixels) {
    const bool same = done == 0 && samples == p.samples_per_pass && active_pixels == p.active_pixels;
    if (!same) {
      // not blocking: every launch waits for its commands, so this write has run before
      // sub_params_ changes again
      sub_params_ = p;
      sub_params_.sample_offset = p.sample_offset + done;
      sub_params_.samples_per_pass = samples;
      sub_params_.active_pixels = active_pixels;
      device_.write(b.params, 0, sizeof(sub_params_), &sub_params_, false);
    }
    return c.launcher->launch(b, same ? p : sub_params_);
  }
  PassOutput run(Candidate& c, const PassBuffers& b, const RenderParams& p, std::uint32_t done, std::uint32_t samples) {
    return run(c, b, p, done, samples, p.active_pixels);
  }

  // The next method of the round renders a launch, timed.
  PassOutput probe(const PassBuffers& b, const RenderParams& p, std::uint32_t done, std::uint32_t samples,
                   std::uint32_t active_pixels) {
    Candidate& c = *queue_.front();
    const auto start = std::chrono::steady_clock::now();
    PassOutput out = run(c, b, p, done, samples, active_pixels);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    probe_seconds_ += seconds;
    const double rate = seconds > 0 ? double(out.rays) / seconds : 0.0;
    if (screening_) c.screen_rate = rate;
    else (c.final_rate < 0 ? c.final_rate : c.final_rate_again) = rate;
    queue_.pop_front();
    if (queue_.empty()) end_round();
    return out;
  }

  // A wave: the samples per pixel of this pass that fill the pool (at least one); the screen
  // takes a quarter of it.
  std::uint32_t round_samples(const RenderParams& p) const {
    const std::uint32_t wave =
        std::clamp<std::uint32_t>(pool_slots_ / std::max<std::uint32_t>(pass_pixel_count(&p), 1), 1, max_per_launch_);
    return screening_ ? std::max<std::uint32_t>(wave / 4, 1) : wave;
  }

  // The fastest of a round (the first of equals); null before any method was timed in it.
  Candidate* best(bool screen) const {
    Candidate* pick = nullptr;
    for (const auto& c : candidates_) {
      const double rate = screen ? c->screen_rate : c->final_rate;
      if (rate >= 0 && (!pick || rate > (screen ? pick->screen_rate : pick->final_rate))) pick = c.get();
    }
    // a render that ended in the final round: its pick among those the final timed
    return pick || screen ? pick : best(true);
  }

  void end_round() {
    if (!screening_) {
      pick_from_final();
      return;
    }
    screening_ = false;
    std::vector<ScreenedMethod> screened;
    for (const auto& c : candidates_) screened.push_back({c->screen_rate, c->method->sorts});
    for (std::size_t i : auto_finalists(screened, kKeep, kFinalists)) queue_.push_back(candidates_[i].get());
    // the default runs first and last in the final, whatever its screen
    if (default_) {
      std::erase(queue_, default_);
      if (queue_.empty()) {  // the screen kept the default alone
        chosen_ = default_;
        return;
      }
      queue_.push_front(default_);
      queue_.push_back(default_);
    } else if (queue_.size() == 1) {  // nothing to compare: the screen's pick
      chosen_ = queue_.front();
      queue_.clear();
    }
  }

  void pick_from_final() {
    if (!default_ || default_->final_rate < 0) {
      chosen_ = best(false);
      return;
    }
    std::vector<double> rates;
    std::size_t default_index = 0;
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
      rates.push_back(candidates_[i]->final_rate);
      if (candidates_[i].get() == default_) default_index = i;
    }
    chosen_ = candidates_[auto_pick(rates, default_index, default_->final_rate_again, kMinMargin)].get();
    if (chosen_ == default_) {
      const Candidate* fastest = best(false);
      if (fastest != default_)
        reason_ = fmt::format("the default: {} was not faster beyond the probe's noise", fastest->method->name);
    } else {
      checks_left_ = kCheckLaunches;
    }
  }

  // The pick's first launches against the default's final rate (the better of its two timings).
  void check_pick(std::uint64_t rays, double seconds) {
    if (checks_left_ == 0 || chosen_ == default_ || seconds <= 0) return;
    check_rays_ += rays;
    check_seconds_ += seconds;
    if (--checks_left_ > 0) return;
    const double rate = double(check_rays_) / check_seconds_;
    const double reference = std::max(default_->final_rate, default_->final_rate_again);
    if (rate < kCheckKeep * reference) {
      reason_ = fmt::format("the default: {} ran at {:.3g} rays/s in the render, below {} x the default's {:.3g}",
                            chosen_->method->name, rate, kCheckKeep, reference);
      chosen_ = default_;
    }
  }

  const Device& device_;
  const RenderSettings& settings_;
  std::vector<std::unique_ptr<Candidate>> candidates_;
  std::deque<Candidate*> queue_;  // the methods still to be timed in this round, in table order
  struct PixelRows {
    DeviceBuffer list;
    std::uint32_t pixels = 0;
  };
  PixelRows screen_rows_, other_rows_;
  bool split_done_ = false;
  bool screening_ = true;
  Candidate* chosen_ = nullptr;
  Candidate* default_ = nullptr;  // the device's default method (device_default_method)
  std::uint32_t checks_left_ = 0;  // launches of the pick still to check against the default
  std::uint64_t check_rays_ = 0;
  double check_seconds_ = 0;
  std::uint32_t pool_slots_ = 1;
  std::uint32_t max_per_launch_ = UINT32_MAX;
  double probe_seconds_ = 0;
  std::string reason_;  // why the pick, when it was not probed
  RenderParams sub_params_{};
};

}  // namespace

std::unique_ptr<PassLauncher> auto_method(const MethodInputs& in) { return std::make_unique<AutoMethod>(in); }

}  // namespace cohort
