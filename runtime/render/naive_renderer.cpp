#include <algorithm>
#include <chrono>

#include "runtime/cl/cl_error.h"
#include "runtime/cl/kernel_program.h"
#include "runtime/render/camera_params.h"
#include "runtime/render/renderer.h"

namespace cohort {
namespace {

using Clock = std::chrono::steady_clock;

RenderParams make_params(const DeviceScene& scene, const SceneCamera& camera, const RenderSettings& s) {
  RenderParams p{};
  p.camera = make_camera_params(camera, s.width, s.height);
  if (s.environment) p.environment = {s.environment->x, s.environment->y, s.environment->z, 0.f};
  p.scene_min = {scene.bounds.lo.x, scene.bounds.lo.y, scene.bounds.lo.z, 0.f};
  p.scene_max = {scene.bounds.hi.x, scene.bounds.hi.y, scene.bounds.hi.z, 0.f};
  p.width = s.width;
  p.height = s.height;
  p.max_depth = s.max_depth;
  p.rr_depth = s.rr_depth;
  p.seed = s.seed;
  p.flags = (s.nee ? RENDER_FLAG_NEE : 0u) | (s.mis ? RENDER_FLAG_MIS : 0u) |
            (s.russian_roulette ? RENDER_FLAG_RUSSIAN_ROULETTE : 0u) |
            (s.environment ? RENDER_FLAG_ENVIRONMENT : 0u);
  p.emitter_count = scene.emitter_count;
  p.emitter_power_total = scene.emitter_power_total;
  // offsets scale with the scene so that neither a millimetre nor a kilometre scene self-intersects
  p.ray_epsilon = 1e-4f * std::max(scene.bounds.diagonal(), 1e-6f);
  return p;
}

}  // namespace

RenderResult render_naive(const ClContext& cl, const ProgramCache& cache, const DeviceScene& scene,
                          const SceneCamera& camera, const RenderSettings& settings, const ProgressCallback& progress) {
  RenderResult result;
  const ProgramBuild build = build_kernel_program(cl, cache, "naive.cl");
  result.compile_seconds = build.seconds;
  result.compile_from_cache = build.from_cache;

  const std::uint32_t pixels = settings.width * settings.height;
  RenderParams params = make_params(scene, camera, settings);
  std::string stage = "render_naive set-up";
  try {
    cl::Kernel kernel(build.program, "render_naive");
    cl::Buffer params_buffer = cl.buffer("render parameters", sizeof(RenderParams), nullptr, CL_MEM_READ_ONLY);
    std::vector<co_float4> zeros(pixels, co_float4{0, 0, 0, 0});
    cl::Buffer film = cl.buffer("film", zeros.size() * sizeof(co_float4), zeros.data());
    const std::uint32_t counters_init[2] = {0, 0};
    cl::Buffer counters = cl.buffer("ray counters", sizeof(counters_init), counters_init);
    cl::Buffer dropped = cl.buffer("dropped-sample counter", sizeof(std::uint32_t), counters_init);
    int arg = 0;
    for (const cl::Buffer* b : std::initializer_list<const cl::Buffer*>{&params_buffer, &scene.nodes, &scene.leaf_triangles, &scene.triangles,
                                &scene.triangle_material, &scene.materials, &scene.emitters, &film, &counters, &dropped})
      kernel.setArg(arg++, *b);

    const bool unbounded = settings.time_limit > 0 && settings.spp == 0;
    const auto t0 = Clock::now();
    std::uint32_t per_pass = 1;
    while (unbounded || result.samples < settings.spp) {
      const std::uint32_t count = unbounded ? per_pass : std::min(per_pass, settings.spp - result.samples);
      params.sample_offset = result.samples;
      params.samples_per_pass = count;
            cl.queue.enqueueWriteBuffer(params_buffer, CL_FALSE, 0, sizeof(params), &params);
      stage = "render_naive pass";
      cl::Event event;
      const std::size_t group = 64;
      cl.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange((pixels + group - 1) / group * group),
                                    cl::NDRange(group), nullptr, &event);
      std::uint32_t pass_rays = 0;
            cl.queue.enqueueReadBuffer(counters, CL_TRUE, 0, sizeof(pass_rays), &pass_rays);
      cl.queue.enqueueWriteBuffer(counters, CL_FALSE, 0, sizeof(std::uint32_t), counters_init);
      const double kernel_time = event_seconds(event);
      result.kernel_seconds["render_naive"] += kernel_time;
      result.rays += pass_rays;
      result.samples += count;
      result.render_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      if (progress) progress({result.samples, unbounded ? 0u : settings.spp, result.rays, result.render_seconds});
      if (settings.time_limit > 0 && result.render_seconds >= settings.time_limit) break;
      // grow passes while they are short, so progress stays live without launch overhead;
      // each pass stays far below 2^32 rays so the 32-bit counter cannot wrap
      const double rays_per_sample = static_cast<double>(pass_rays) / count;
      if (kernel_time < 0.25 && rays_per_sample * per_pass * 2 < 1e9) per_pass *= 2;
    }
    stage = "reading the film";
    std::vector<co_float4> sums(pixels);
    cl.queue.enqueueReadBuffer(film, CL_TRUE, 0, sums.size() * sizeof(co_float4), sums.data());
    std::uint32_t dropped_count = 0;
    cl.queue.enqueueReadBuffer(dropped, CL_TRUE, 0, sizeof(dropped_count), &dropped_count);
    result.dropped_samples = dropped_count;
    result.image = Image(static_cast<int>(settings.width), static_cast<int>(settings.height));
    const float inv = result.samples ? 1.f / static_cast<float>(result.samples) : 0.f;
    for (std::uint32_t i = 0; i < pixels; ++i) {
      result.image.rgb[3 * i + 0] = sums[i].x * inv;
      result.image.rgb[3 * i + 1] = sums[i].y * inv;
      result.image.rgb[3 * i + 2] = sums[i].z * inv;
    }
  } catch (const cl::Error& e) {
    throw DeviceError(describe(e, stage));
  }
  return result;
}

}  // namespace cohort
