#pragma once

#include <cstdint>

#include "kernels/common/core/types.h"
#include "runtime/scene/scene.h"

namespace cohort {

// The device camera for an image of width x height; vfov is vertical, as docs/bench-protocol.md.
CameraParams make_camera_params(const SceneCamera& camera, std::uint32_t width, std::uint32_t height);

}  // namespace cohort
