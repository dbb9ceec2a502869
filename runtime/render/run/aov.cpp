#include "runtime/render/run/aov.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <sstream>

#include "kernels/common/core/types.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/render/render_params.h"
#include "runtime/util/error.h"

namespace cohort {

AovSelection parse_aov_list(const std::string& list) {
  AovSelection selection;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name == "albedo")
      selection.albedo = true;
    else if (name == "normal")
      selection.normal = true;
    else if (name == "depth")
      selection.depth = true;
    else
      throw InputError(fmt::format("--aov: unknown AOV '{}' (known: albedo, normal, depth)", name));
  }
  if (!selection.any())
    throw InputError(fmt::format("--aov: no AOV named in '{}' (known: albedo, normal, depth)", list));
  return selection;
}

AovImages render_aovs(const Device& device, const ProgramCache& cache, const DeviceScene& scene,
                      const SceneCamera& camera, const RenderSettings& settings,
                      const std::vector<std::uint32_t>& pixel_samples) {
  const std::uint32_t pixels = settings.width * settings.height;
  if (pixel_samples.size() != pixels) throw std::logic_error("render_aovs: one sample count per pixel");
  const std::uint32_t samples =
      pixel_samples.empty() ? 0u : *std::max_element(pixel_samples.begin(), pixel_samples.end());
  const DeviceProgram program = device.build_program(cache, "aov", scene.build_options);
  DeviceKernel kernel = program.kernel("render_aov");
  RenderParams params = make_render_params(scene, camera, settings);
  RenderAovArgs args;
  args.scene = scene.kernel_buffers();
  args.params = device.allocate("AOV render parameters", sizeof(RenderParams), nullptr, Access::read_only);
  args.aov_albedo = device.allocate("albedo and depth sums", std::size_t(pixels) * sizeof(co_float4));
  args.aov_normal = device.allocate("normal sums and hits", std::size_t(pixels) * sizeof(co_float4));
  device.fill(args.aov_albedo, 0u, std::size_t(pixels) * 4);
  device.fill(args.aov_normal, 0u, std::size_t(pixels) * 4);
  args.aov_samples = device.allocate("AOV sample counts", std::size_t(pixels) * sizeof(std::uint32_t),
                                     pixel_samples.data(), Access::read_only);
  args.bind(kernel);
  // launches of at most ~16M camera rays, short enough for a GPU's watchdog; the sums go on in
  // sample order from one launch to the next, so the split changes no bit
  const std::uint32_t per_launch = std::max<std::uint32_t>(1, (1u << 24) / std::max<std::uint32_t>(pixels, 1));
  for (std::uint32_t done = 0; done < samples;) {
    params.sample_offset = done;
    params.samples_per_pass = std::min(per_launch, samples - done);
    device.write(args.params, 0, sizeof(params), &params);
    device.launch(kernel, pixels);
    done += params.samples_per_pass;
  }
  std::vector<co_float4> albedo_sums(pixels), normal_sums(pixels);
  device.read(args.aov_albedo, 0, albedo_sums.size() * sizeof(co_float4), albedo_sums.data());
  device.read(args.aov_normal, 0, normal_sums.size() * sizeof(co_float4), normal_sums.data());

  AovImages out{Image(int(settings.width), int(settings.height)), Image(int(settings.width), int(settings.height)),
                std::vector<float>(pixels)};
  for (std::uint32_t i = 0; i < pixels; ++i) {
    const float inv = pixel_samples[i] ? 1.f / float(pixel_samples[i]) : 0.f;
    const co_float4 a = albedo_sums[i], n = normal_sums[i];
    float* albedo = &out.albedo.rgb[std::size_t(i) * 3];
    float* normal = &out.normal.rgb[std::size_t(i) * 3];
    albedo[0] = a.x * inv, albedo[1] = a.y * inv, albedo[2] = a.z * inv;
    normal[0] = n.x * inv, normal[1] = n.y * inv, normal[2] = n.z * inv;
    out.depth[i] = n.w > 0.f ? a.w / n.w : std::numeric_limits<float>::infinity();
  }
  return out;
}

std::vector<ExrLayer> aov_layers(const AovImages& aovs, const AovSelection& selection) {
  std::vector<ExrLayer> layers;
  if (selection.albedo) layers.push_back({{"albedo.R", "albedo.G", "albedo.B"}, aovs.albedo.rgb});
  if (selection.normal) layers.push_back({{"N.X", "N.Y", "N.Z"}, aovs.normal.rgb});
  if (selection.depth) layers.push_back({{"depth.Z"}, aovs.depth});
  return layers;
}

}  // namespace cohort
