// What each process of a render did beside the image: its serial part (load, build) beside its
// render time, so scaling losses show, and each device's share. Filled once where the passes end
// (rank_figures), sent whole from the other MPI ranks to rank 0 and written whole into --stats: the
// JSON names are the fields' own (NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE below), so a figure is added
// here and nowhere else.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/render/run/multi_device.h"
#include "runtime/render/scene/prepared_scene.h"

namespace cohort {

// One device's share: passes, rays, rays/s while busy, busy time.
struct DeviceFigures {
  std::string name, platform, driver;
  std::uint32_t compute_units = 0;
  std::uint32_t passes = 0;
  std::uint32_t samples = 0;
  std::uint64_t rays = 0;
  double rays_per_second = 0;  // over busy_seconds
  double busy_seconds = 0;
  double upload_seconds = 0;
  double compile_seconds = 0;
  std::vector<double> pass_kernel_seconds;  // device time of each pass, in the order rendered
  std::uint32_t max_nodes_per_ray = 0;
};

struct RankFigures {
  int rank = 0;
  std::string host;
  double load_seconds = 0;
  double build_seconds = 0;
  double compile_seconds = 0;  // the slowest device's
  double render_seconds = 0;   // the slowest device's
  std::vector<DeviceFigures> devices;
};

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DeviceFigures, name, platform, driver, compute_units, passes, samples, rays,
                                   rays_per_second, busy_seconds, upload_seconds, compile_seconds,
                                   pass_kernel_seconds, max_nodes_per_ray)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RankFigures, rank, host, load_seconds, build_seconds, compile_seconds,
                                   render_seconds, devices)

DeviceFigures device_figures(const DeviceRun& run);
RankFigures rank_figures(int rank, const std::string& host, const PreparedScene& prepared,
                         const std::vector<DeviceRun>& runs);

}  // namespace cohort
