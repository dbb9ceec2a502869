#include "runtime/render/run/pass_driver.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <iterator>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "kernels/common/core/contract.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/render/run/launch_log.h"
#include "runtime/render/run/pass_job.h"
#include "runtime/util/error.h"

namespace cohort {

namespace {

// The image film on the device: each pass is added to it there (film_add), and only the pass's
// per-group totals come back, instead of a partial film per pass.
struct DeviceImage {
  DeviceBuffer film, group_sums;
  DeviceKernel add;
  double compile_seconds = 0, last_seconds = 0;
  std::vector<co_float4> groups;

  std::size_t group = 1;  // work items per group: a power of two, as the kernel's reduction needs

  DeviceImage(const Device& cl, const ProgramCache& cache, const FilmState& start, std::uint32_t pixels) {
    const DeviceProgram program = cl.build_program(cache, "film");
    compile_seconds = program.seconds;
    add = program.kernel("film_add");
    while (group * 2 <= std::min<std::size_t>(FILM_WG, add.max_group())) group *= 2;
    groups.resize((pixels + group - 1) / group + 1);  // the last entry: the dropped-sample count
    film = cl.allocate("image film", std::size_t(pixels) * sizeof(co_float4), start.sums.data());
    group_sums = cl.allocate("pass totals", groups.size() * sizeof(co_float4));
  }

  // image += pass in one launch, then one read: the pass's sums added over the pixels, and its
  // dropped samples
  void add_pass(const Device& cl, const PassBuffers& pass, std::uint32_t pixels, PassFilm& out) {
    const auto group_count = static_cast<std::uint32_t>(groups.size() - 1);
    FilmAddArgs args;
    args.image = film;
    args.pass = pass.film;
    args.pixels = pixels;
    args.group_sums = group_sums;
    args.dropped = pass.dropped;
    args.groups = group_count;
    args.bind(add);
    const DeviceEvent event = cl.launch(add, pixels, group);
    cl.read(group_sums, 0, groups.size() * sizeof(co_float4), groups.data());
    last_seconds = event.seconds();
    out.totals = {};
    for (std::size_t g = 0; g < group_count; ++g) {
      out.totals[0] += groups[g].x;
      out.totals[1] += groups[g].y;
      out.totals[2] += groups[g].z;
    }
    out.dropped = co_as_uint(groups.back().x);
  }

  std::vector<co_float4> read(const Device& cl, std::uint32_t pixels) const {
    std::vector<co_float4> sums(pixels);
    cl.read(film, 0, sums.size() * sizeof(co_float4), sums.data());
    return sums;
  }
};

}  // namespace

void keep_worst(std::vector<StragglerRay>& worst, std::vector<StragglerRay> more, std::size_t keep) {
  worst.insert(worst.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
  std::stable_sort(worst.begin(), worst.end(),
                   [](const StragglerRay& a, const StragglerRay& b) { return a.nodes > b.nodes; });
  if (worst.size() > keep) worst.resize(keep);
}

RenderResult drive_passes(const Device& cl, const ProgramCache& cache, const RenderParams& base_params,
                          const RenderSettings& settings, const ProgressCallback& progress,
                          const RenderControl& control, PassLauncher& launcher) {
  using Clock = std::chrono::steady_clock;
  RenderResult result;
  std::optional<PassJob> own_job;
  PassSource& source = control.passes ? *control.passes : own_job.emplace(settings, progress, control, 1, 1);
  const std::uint32_t pixels = settings.width * settings.height;
  PassBuffers buffers;
  buffers.params = cl.allocate("render parameters", sizeof(RenderParams), nullptr, Access::read_only);
  buffers.film = cl.allocate("film", std::size_t(pixels) * sizeof(co_float4));
  buffers.dropped = cl.allocate("dropped-sample counter", sizeof(std::uint32_t));
  // adaptive passes list their pixels here; other renders bind a one-entry buffer they never read
  buffers.pixel_list = cl.allocate("pass pixel list", std::size_t(settings.target_error > 0 ? pixels : 1) *
                                                          sizeof(std::uint32_t));
  // the list in buffers.pixel_list, held so that a new round's list cannot reuse its address
  std::shared_ptr<const std::vector<std::uint32_t>> listed;

  // one device alone keeps the image on the device: no partial film per pass crosses to the host
  std::optional<DeviceImage> image;
  if (const FilmState* start = source.device_keeps_image([&] { return image->read(cl, pixels); })) {
    image.emplace(cl, cache, *start, pixels);
    result.compile_seconds += image->compile_seconds;
  }

  RenderParams params = base_params;
  cl.finish();  // buffers placed on the device before the clock starts (their upload is not rendering)
  const auto t0 = Clock::now();
  const std::uint32_t max_samples_per_pass = launcher.max_samples_per_launch();
  std::uint32_t per_launch = std::clamp<std::uint32_t>(launcher.first_launch_samples(), 1, max_samples_per_pass);
  source.device_ready();
  while (const auto sample_pass = source.next()) {
    const auto pass_start = Clock::now();
    // every pass sums from zero, so its partial film is the same on any device (pass_schedule.h)
    cl.fill(buffers.film, 0u, std::size_t(pixels) * 4);  // 4 words per pixel; all-zero bits are 0.0f
    cl.fill(buffers.dropped, 0u, 1);
    PassFilm film{*sample_pass, {}, 0, 0};
    // a round's passes share one list: uploaded when the round changes
    const std::vector<std::uint32_t>* pass_pixels = sample_pass->pixels.get();
    if (pass_pixels && pass_pixels != listed.get()) {
      if (pass_pixels->empty() || pass_pixels->size() > pixels)
        throw DeviceError(fmt::format("pass {}: a list of {} pixels for an image of {}", sample_pass->index,
                                      pass_pixels->size(), pixels));
      cl.write(buffers.pixel_list, 0, pass_pixels->size() * sizeof(std::uint32_t), pass_pixels->data());
      listed = sample_pass->pixels;
    }
    params.active_pixels = pass_pixels ? static_cast<std::uint32_t>(pass_pixels->size()) : 0u;
    double pass_kernel_seconds = 0;
    std::vector<std::uint32_t> extension_steps;
    for (std::uint32_t done = 0; done < sample_pass->samples;) {
      const std::uint32_t count = std::min(per_launch, sample_pass->samples - done);
      params.sample_offset = sample_pass->first_sample + done;
      params.samples_per_pass = count;
      // non-blocking: every pass function waits for its launches before it returns (a blocking
      // read of its counters, or its kernel events), so this write has run before `params` changes
      cl.write(buffers.params, 0, sizeof(params), &params, false);
      const PassOutput out = launcher.launch(buffers, params);
      film.rays += out.rays;
      result.max_nodes_per_ray = std::max(result.max_nodes_per_ray, out.max_steps);
      if (settings.straggler_rays) {
        extension_steps.insert(extension_steps.end(), out.extension_steps.begin(), out.extension_steps.end());
        keep_worst(result.worst_rays, out.worst_rays, settings.straggler_rays);
      }
      add_seconds(result.kernel_seconds, out.kernel_seconds);
      result.pass_host_reads.push_back(out.host_reads);
      result.pass_sort_launches.push_back(out.sort_launches);
      done += count;
      // within a pass the film is a running sum, so launch sizes do not change the image: grow
      // them while they are short, keeping per-launch overhead small
      double launch_seconds = 0;
      for (const auto& [name, s] : out.kernel_seconds) launch_seconds += s;
      pass_kernel_seconds += launch_seconds;
      if (launch_seconds < 0.25 && per_launch * 2 <= max_samples_per_pass) per_launch *= 2;
    }
    if (image) {
      image->add_pass(cl, buffers, pixels, film);
      add_seconds(result.kernel_seconds, {{"film", image->last_seconds}});
      pass_kernel_seconds += image->last_seconds;
    } else {
      film.sums.resize(pixels);
      cl.read(buffers.film, 0, film.sums.size() * sizeof(co_float4), film.sums.data());
      std::uint32_t dropped = 0;
      cl.read(buffers.dropped, 0, sizeof(dropped), &dropped);
      film.dropped = dropped;
    }
    result.rays += film.rays;
    result.samples += sample_pass->samples;
    ++result.passes;
    result.pass_kernel_seconds.push_back(pass_kernel_seconds);
    if (settings.straggler_rays && !extension_steps.empty()) {
      // the 99.99th percentile is one order statistic: no need to sort the pass's millions of counts
      const auto p9999 = extension_steps.begin() + std::ptrdiff_t(extension_steps.size() / 10000);
      std::nth_element(extension_steps.begin(), p9999, extension_steps.end(), std::greater<>());
      result.pass_stragglers.push_back({*std::max_element(extension_steps.begin(), p9999 + 1), *p9999});
    }
    result.busy_seconds += std::chrono::duration<double>(Clock::now() - pass_start).count();
    source.deliver(std::move(film));
  }
  // the image goes to the source before this device (and its memory) goes away
  if (image) source.deliver_image(image->read(cl, pixels));
  result.render_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  launcher.report(result);
  if (own_job) own_job->finish_into(result);
  return result;
}

}  // namespace cohort
