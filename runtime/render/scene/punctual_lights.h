// The device table of KHR_lights_punctual lights NEE picks from, by power (docs/lights.md).
#pragma once

#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/scene/scene.h"

namespace cohort {

struct PunctualTable {
  std::vector<PunctualLight> lights;
  double power = 0;  // total radiant flux (luminance-weighted), to balance against other lights
};

// Flux of one light: 4 pi I for a point light, 2 pi (1 - cos) I for a spot, with the cone angle
// halfway between inner and outer; I is the luminance of the intensity.
double punctual_power(const SceneLight& light);

PunctualTable make_punctual_table(const std::vector<SceneLight>& lights);

}  // namespace cohort
