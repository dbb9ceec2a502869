// The first-hit AOVs of a render: one launch sequence on rank 0's first device after the
// passes, so they are the same bits however many devices, ranks or which method made the beauty.
#include <chrono>

#include "runtime/render/run/render_run.h"

namespace cohort {

void render_first_hit_aovs(const PreparedRender& render, RenderOutcome& outcome) {
  if (!render.input.first_hit_aovs()) return;
  const auto start = std::chrono::steady_clock::now();
  const FilmState& film = outcome.film;
  const std::vector<std::uint32_t> samples =
      film.pixel_samples.empty() ? std::vector<std::uint32_t>(film.sums.size(), film.samples) : film.pixel_samples;
  render.pool->run_on(0, render.scene, [&](const Device& device, const DeviceScene& scene) {
    outcome.aovs = render_aovs(device, render.cache, scene, render.scene.camera, render.input.settings, samples);
  });
  outcome.aov_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace cohort
