// First-hit AOVs (arbitrary output variables) of a render: albedo, shading normal and depth, made
// by kernels/common/wavefront/aov_kernel.h over the camera rays of the beauty's samples, and written as extra
// EXR channels with the names docs/decisions.md fixes (those OIDN and compositors read).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/program_cache.h"
#include "runtime/image/image.h"
#include "runtime/render/scene/device_scene.h"
#include "runtime/render/render_settings.h"

namespace cohort {

struct AovSelection {
  bool albedo = false;
  bool normal = false;
  bool depth = false;
  bool any() const { return albedo || normal || depth; }
};

// "albedo,normal,depth" or any subset; throws InputError naming a name that is none of them.
AovSelection parse_aov_list(const std::string& list);

// Per pixel: albedo and normal averaged over every sample (an escaped ray counts as 0), depth
// averaged over the samples whose camera ray hits (infinity when none does).
struct AovImages {
  Image albedo, normal;
  std::vector<float> depth;
};

// The AOVs of samples [0, pixel_samples[i]) of each pixel i (the film's counts: adaptive
// sampling's differ per pixel), on one device; the same bits whatever method rendered the beauty.
AovImages render_aovs(const Device& device, const ProgramCache& cache, const DeviceScene& scene,
                      const SceneCamera& camera, const RenderSettings& settings,
                      const std::vector<std::uint32_t>& pixel_samples);

// The selected AOVs as EXR layers: albedo.R/G/B, N.X/Y/Z, depth.Z.
std::vector<ExrLayer> aov_layers(const AovImages& aovs, const AovSelection& selection);

}  // namespace cohort
