// The first-hit AOVs of `cohort render`: one launch sequence on rank 0's first device after the
// passes, so they are the same bits however many devices, ranks or which method made the beauty.
#include "runtime/cli/render_steps.h"

namespace cohort {

std::optional<AovImages> render_first_hit_aovs(const PreparedRender& render, const FilmState& film) {
  if (!render.plan.aovs.any() && !render.plan.command.denoise) return std::nullopt;
  const std::vector<std::uint32_t> samples =
      film.pixel_samples.empty() ? std::vector<std::uint32_t>(film.sums.size(), film.samples) : film.pixel_samples;
  std::optional<AovImages> aovs;
  render.pool->run_on(0, render.scene, [&](const Device& device, const DeviceScene& scene) {
    aovs = render_aovs(device, render.cache, scene, render.scene.camera, render.plan.settings(), samples);
  });
  return aovs;
}

}  // namespace cohort
