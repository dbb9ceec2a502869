// auto: every other method renders one sample pass of the image in turn, timed; the fastest renders
// the rest. Every method gives each pass the same bits (pass_schedule.h), so the probe's passes are
// part of the image, not thrown away: the probe costs only the difference between the slower
// methods and the fastest, on one pass each (DECISIONS.md, round 2: its time counts).
#include <chrono>
#include <optional>

#include "runtime/render/methods.h"
#include "runtime/render/multi_device.h"
#include "runtime/render/pass_job.h"

namespace cohort {
namespace {

// Hands out at most `budget` passes of another source, then says the device is done.
class PassBudget final : public PassSource {
 public:
  PassBudget(PassSource& source, std::uint32_t budget) : source_(source), left_(budget) {}
  void device_ready() override { source_.device_ready(); }
  std::optional<SamplePass> next() override {
    if (left_ == 0) return std::nullopt;
    --left_;
    auto pass = source_.next();
    if (pass) ++taken_;
    return pass;
  }
  void deliver(PassFilm film) override { source_.deliver(std::move(film)); }
  void abort() override { source_.abort(); }
  const FilmState* device_keeps_image(std::function<std::vector<co_float4>()> read_image) override {
    return source_.device_keeps_image(std::move(read_image));
  }
  void deliver_image(std::vector<co_float4> sums) override { source_.deliver_image(std::move(sums)); }
  std::uint32_t taken() const { return taken_; }

 private:
  PassSource& source_;
  std::uint32_t left_;
  std::uint32_t taken_ = 0;
};

}  // namespace

RenderResult render_auto(const MethodInputs& in) {
  std::optional<PassJob> own_job;
  PassSource& source = in.control.passes ? *in.control.passes : own_job.emplace(in.settings, in.progress, in.control, 1, 1);
  const ProgressCallback quiet;  // the job reports progress
  auto run = [&](const Method& m, PassSource& passes) {
    RenderSettings s = in.settings;
    s.method = m.name;
    RenderControl c;  // the job holds the checkpoints, the stop and the resumed film
    c.passes = &passes;
    return m.render(MethodInputs{in.device, in.cache, in.scene, in.params, s, quiet, c});
  };
  const auto start = std::chrono::steady_clock::now();
  std::vector<DeviceRun> runs;
  const Method* best = nullptr;
  double best_rate = -1, probe_seconds = 0;
  std::map<std::string, double> rates;
  for (const Method& m : methods()) {
    if (m.render == render_auto) continue;
    PassBudget one(source, 1);
    RenderResult r = run(m, one);
    if (one.taken() == 0) break;  // the image has fewer passes than there are methods
    // the pass's rays over its wall time on the device (setting up the method is not counted:
    // programs come from the cache after the first run, and the other methods pay it too)
    const double rate = r.busy_seconds > 0 ? double(r.rays) / r.busy_seconds : 0.0;
    rates[m.name] = rate;
    probe_seconds += r.render_seconds;
    if (rate > best_rate) {
      best = &m;
      best_rate = rate;
    }
    runs.push_back(DeviceRun{{}, std::move(r), 0});
  }
  // the pick's figures first: the merge takes the method's settings (pool, code) from the first
  if (best) runs.insert(runs.begin(), DeviceRun{{}, run(*best, source), 0});
  RenderResult result = merge_device_results(runs);
  result.auto_choice.method = best ? best->name : "";
  result.auto_choice.probe_seconds = probe_seconds;
  result.auto_choice.probe_rays_per_second = std::move(rates);
  // with shared passes, this device's time from its first pass to its last (as a method's)
  result.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (own_job) own_job->finish_into(result);
  return result;
}

}  // namespace cohort
