// auto: the other methods take turns at the launches of the image's first passes, timed; the
// fastest renders the rest. Every method adds the same bits for the same samples (pass_driver.h:
// a launch's samples join the pass film in sample order), so the probe's launches are part of the
// image, not thrown away: the probe costs only the difference between the slower methods and the
// fastest on the samples each probed (DECISIONS.md, round 2: its time counts).
//
// Two rounds keep that difference small. The screen gives each method a quarter of a wave (the
// samples per pixel that fill the wavefront pool): enough to tell a method that is far behind
// (the megakernel on a GPU, the wavefront on a CPU), whose full wave would cost the most. The
// final gives each method within kKeep of the screen's best one full wave, the size at which
// sorting pays or does not, and picks the fastest there. All methods share one pool.
#include <algorithm>
#include <chrono>
#include <deque>
#include <memory>

#include "runtime/render/launch_log.h"
#include "runtime/render/methods.h"
#include "runtime/render/stages/wavefront_loop.h"

namespace cohort {
namespace {

// Methods at least this fraction of the screen's best rate go on to the final round.
constexpr double kKeep = 0.8;

struct Candidate {
  const Method* method = nullptr;
  RenderSettings settings;  // the render's, named for the method (its launcher keeps a reference)
  std::unique_ptr<PassLauncher> launcher;
  double screen_rate = -1, final_rate = -1;  // rays per second; -1: not probed in that round
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
  }

  std::uint32_t max_samples_per_launch() const override { return max_per_launch_; }
  // whole passes: the probe splits them into its own launches
  std::uint32_t first_launch_samples() const override { return max_per_launch_; }

  PassOutput launch(const PassBuffers& b, const RenderParams& p) override {
    PassOutput total;
    for (std::uint32_t done = 0; done < p.samples_per_pass;) {
      const std::uint32_t left = p.samples_per_pass - done;
      Candidate* c = chosen_ ? chosen_ : queue_.front();
      const std::uint32_t samples = chosen_ ? left : std::min(round_samples(p), left);
      if (samples != p.samples_per_pass) {
        // the launch's own parameters; not blocking: every launch waits for its commands, so this
        // write has run before sub_params_ changes again
        sub_params_ = p;
        sub_params_.sample_offset = p.sample_offset + done;
        sub_params_.samples_per_pass = samples;
        device_.write(b.params, 0, sizeof(sub_params_), &sub_params_, false);
      }
      const auto start = std::chrono::steady_clock::now();
      PassOutput out = c->launcher->launch(b, samples == p.samples_per_pass ? p : sub_params_);
      if (!chosen_) {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        probe_seconds_ += seconds;
        (screening_ ? c->screen_rate : c->final_rate) = seconds > 0 ? double(out.rays) / seconds : 0.0;
        queue_.pop_front();
        if (queue_.empty()) end_round();
      }
      add_output(total, std::move(out), settings_.straggler_rays);
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
    a.probe_seconds = probe_seconds_;
    for (const auto& c : candidates_) {
      if (c->screen_rate >= 0) a.probe_rays_per_second[c->method->name] = c->screen_rate;
      if (c->final_rate >= 0) a.final_rays_per_second[c->method->name] = c->final_rate;
    }
  }

 private:
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
      chosen_ = best(false);
      return;
    }
    screening_ = false;
    const double fastest = best(true)->screen_rate;
    for (const auto& c : candidates_)
      if (c->screen_rate >= kKeep * fastest) queue_.push_back(c.get());
    if (queue_.size() == 1) {  // nothing to compare: the screen's pick
      chosen_ = queue_.front();
      queue_.clear();
    }
  }

  const Device& device_;
  const RenderSettings& settings_;
  std::vector<std::unique_ptr<Candidate>> candidates_;
  std::deque<Candidate*> queue_;  // the methods still to be timed in this round, in table order
  bool screening_ = true;
  Candidate* chosen_ = nullptr;
  std::uint32_t pool_slots_ = 1;
  std::uint32_t max_per_launch_ = UINT32_MAX;
  double probe_seconds_ = 0;
  RenderParams sub_params_{};
};

}  // namespace

std::unique_ptr<PassLauncher> auto_method(const MethodInputs& in) { return std::make_unique<AutoMethod>(in); }

}  // namespace cohort
