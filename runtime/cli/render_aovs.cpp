// The first-hit AOVs of `cohort render`: one launch sequence on rank 0's first device after the
// passes, so they are the same bits however many devices, ranks or which method made the beauty.
#include "runtime/cli/render_steps.h"

namespace cohort {

std::optional<AovImages> render_first_hit_aovs(const PreparedRender& render, const FilmState& film) {
  if (!render.plan.aovs.any() && !render.plan.command.denoise) return std::nullopt;
  const std::unique_ptr<Device> device = render.open_devices(0);
  const DeviceScene scene = upload_scene(*device, render.scene.tree, render.scene.tables, render.scene.bvh());
  return render_aovs(*device, render.cache, scene, render.scene.camera, render.plan.settings(),
                     film.pixel_samples.empty() ? std::vector<std::uint32_t>(film.sums.size(), film.samples)
                                                : film.pixel_samples);
}

}  // namespace cohort
