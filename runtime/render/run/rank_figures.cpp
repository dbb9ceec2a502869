#include "runtime/render/run/rank_figures.h"

#include <algorithm>

namespace cohort {

DeviceFigures device_figures(const DeviceRun& run) {
  const RenderResult& r = run.result;
  return {.name = run.device.name,
          .platform = run.device.platform_name,
          .driver = run.device.driver_version,
          .compute_units = run.device.compute_units,
          .passes = r.passes,
          .samples = r.samples,
          .rays = r.rays,
          .rays_per_second = r.busy_seconds > 0 ? double(r.rays) / r.busy_seconds : 0.0,
          .busy_seconds = r.busy_seconds,
          .upload_seconds = run.upload_seconds,
          .compile_seconds = r.compile_seconds,
          .pass_kernel_seconds = r.pass_kernel_seconds,
          .max_nodes_per_ray = r.max_nodes_per_ray};
}

RankFigures rank_figures(int rank, const std::string& host, const PreparedScene& prepared,
                         const std::vector<DeviceRun>& runs) {
  RankFigures figures{.rank = rank,
                      .host = host,
                      .load_seconds = prepared.load_seconds,
                      .build_seconds = prepared.build_seconds()};
  for (const auto& run : runs) {
    figures.devices.push_back(device_figures(run));
    figures.render_seconds = std::max(figures.render_seconds, run.result.render_seconds);
    figures.compile_seconds = std::max(figures.compile_seconds, run.result.compile_seconds);
  }
  return figures;
}

}  // namespace cohort
