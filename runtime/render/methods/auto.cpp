// auto: a short probe of every other method on this scene and device, then the whole render with
// the fastest. Every method gives the same image bit for bit, so the pick changes the speed only.
// The probe's time counts in the render's (DECISIONS.md, round 2).
#include <chrono>

#include "runtime/render/methods.h"

namespace cohort {

RenderResult render_auto(const MethodInputs& in) {
  const auto start = std::chrono::steady_clock::now();
  // one sample per pixel at the render's size: the rays' coherence is the render's, the cost small
  RenderSettings probe = in.settings;
  probe.spp = 1;
  probe.time_limit = 0;
  probe.pass_samples = 0;
  probe.straggler_rays = 0;
  RenderControl control;  // no checkpoint, no resumed film, no shared passes: the probe's image is dropped
  control.stop_requested = in.control.stop_requested;
  const ProgressCallback quiet;
  const Method* best = nullptr;
  double best_rate = -1;
  std::map<std::string, double> rates;
  for (const Method& m : methods()) {
    if (m.render == render_auto) continue;
    probe.method = m.name;
    const RenderResult r = m.render(MethodInputs{in.device, in.cache, in.scene, in.params, probe, quiet, control});
    const double rate = r.render_seconds > 0 ? double(r.rays) / r.render_seconds : 0.0;
    rates[m.name] = rate;
    if (rate > best_rate) {
      best = &m;
      best_rate = rate;
    }
  }
  const double probe_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RenderSettings chosen = in.settings;
  chosen.method = best->name;
  RenderResult result =
      best->render(MethodInputs{in.device, in.cache, in.scene, in.params, chosen, in.progress, in.control});
  result.render_seconds += probe_seconds;
  result.auto_choice.method = best->name;
  result.auto_choice.probe_seconds = probe_seconds;
  result.auto_choice.probe_rays_per_second = std::move(rates);
  return result;
}

}  // namespace cohort
