#pragma once

#include "kernels/common/core/types.h"
#include "runtime/render/scene/device_scene.h"
#include "runtime/render/render_settings.h"

namespace cohort {

// The per-render constants every rendering kernel reads.
RenderParams make_render_params(const DeviceScene& scene, const SceneCamera& camera, const RenderSettings& s);

}  // namespace cohort
