// Presets that make a scene render the same way in every renderer (docs/bench-protocol.md).
#pragma once

#include <array>
#include <optional>

#include "runtime/render/scene/prepared_scene.h"
#include "runtime/render/render_settings.h"

namespace cohort {

// White sky: one two-sided Lambertian of albedo 0.5 on every triangle, flat normals, a constant
// environment of radiance 1, the protocol camera, at most 5 segments, no Russian roulette.
void apply_white_sky(PreparedScene& scene, RenderSettings& settings);
// Its settings alone (the sky, 5 segments, no Russian roulette), for a scene made white already.
void apply_white_sky_settings(RenderSettings& settings);

// A camera at fractions of the scene bounds: eye = lo + f_eye * (hi - lo), looking at
// lo + f_target * (hi - lo), +Y up (the protocol's interior view).
SceneCamera camera_from_bounds(const Bounds& bounds, const std::array<float, 6>& fractions, float vfov_degrees);

}  // namespace cohort
