#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <fstream>

#include "runtime/backend/device_choice.h"
#include "runtime/backend/open_device.h"
#include "runtime/cli/commands.h"
#include "runtime/cli/output_paths.h"
#include "runtime/cli/parse_values.h"
#include "runtime/cli/progress.h"
#include "runtime/render/environment_map.h"
#include "runtime/render/prepared_scene.h"
#include "runtime/render/scene_memory.h"
#include "runtime/render/methods.h"
#include "runtime/render/renderer.h"
#include "runtime/render/workloads.h"
#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"
#include "runtime/util/hash.h"
#include "runtime/util/median.h"
#include "runtime/cli/interrupt.h"
#include "runtime/render/checkpoint.h"
#include "runtime/render/multi_device.h"
#include "runtime/render/pass_job.h"
#ifdef COHORT_HAVE_MPI
#include "runtime/mpi/pass_exchange.h"
#endif

namespace cohort {
namespace {

#ifndef COHORT_HAVE_MPI
class MpiSession {};  // never made: without MPI every render is one process
#endif

std::string this_host() {
  std::array<char, 256> name{};
  return gethostname(name.data(), name.size() - 1) == 0 ? std::string(name.data()) : std::string();
}

// One device's share of the render: passes, rays, rays/s while busy, busy time.
nlohmann::json device_json(const DeviceRun& run) {
  const RenderResult& r = run.result;
  return {{"name", run.device.name}, {"platform", run.device.platform_name}, {"driver", run.device.driver_version},
          {"compute_units", run.device.compute_units}, {"passes", r.passes}, {"samples", r.samples},
          {"rays", r.rays}, {"rays_per_second", r.busy_seconds > 0 ? double(r.rays) / r.busy_seconds : 0.0},
          {"busy_seconds", r.busy_seconds}, {"upload_seconds", run.upload_seconds},
          {"compile_seconds", r.compile_seconds}, {"pass_kernel_seconds", r.pass_kernel_seconds},
          {"max_nodes_per_ray", r.max_nodes_per_ray}};
}

// One process's serial part (load, build) beside its render time, so scaling losses are visible.
nlohmann::json rank_json(int rank, const std::string& host, const PreparedScene& prepared,
                         const std::vector<DeviceRun>& runs) {
  nlohmann::json devices = nlohmann::json::array();
  double render_seconds = 0, compile_seconds = 0;
  for (const auto& run : runs) {
    devices.push_back(device_json(run));
    render_seconds = std::max(render_seconds, run.result.render_seconds);
    compile_seconds = std::max(compile_seconds, run.result.compile_seconds);
  }
  return {{"rank", rank}, {"host", host}, {"load_seconds", prepared.load_seconds},
          {"build_seconds", prepared.tree.stats.build_seconds}, {"compile_seconds", compile_seconds},
          {"render_seconds", render_seconds}, {"devices", devices}};
}

nlohmann::json stats_json(const RenderCommand& cmd, const nlohmann::json& ranks, const PreparedScene& prepared,
                          const RenderResult& r, const OutputPaths& out, const PassJob::ImageMean& mean) {
  nlohmann::json j;
  j["image_mean"] = {{"rgb", mean.mean}, {"standard_error", mean.standard_error}};
  j["scene"] = cmd.scene.string();
  j["method"] = cmd.settings.method;
  nlohmann::json devices = nlohmann::json::array();
  for (const auto& rank : ranks)
    for (auto d : rank["devices"]) {
      d["rank"] = rank["rank"];
      devices.push_back(d);
    }
  j["backend"] = cmd.backend;
  j["device"] = devices.at(0);  // the first device, as before several devices
  j["devices"] = devices;
  j["ranks"] = ranks;
  j["passes"] = r.passes;
  // stragglers show as passes far slower than the median, and as rays that visit much of the tree
  std::vector<double> pass_seconds;
  std::uint32_t max_nodes = 0;
  for (const auto& d : devices) {
    for (const auto& s : d["pass_kernel_seconds"]) pass_seconds.push_back(s.get<double>());
    max_nodes = std::max(max_nodes, d["max_nodes_per_ray"].get<std::uint32_t>());
  }
  j["pass_seconds"] = {{"median", median(pass_seconds)},
                       {"max", pass_seconds.empty() ? 0.0 : *std::max_element(pass_seconds.begin(), pass_seconds.end())}};
  j["max_nodes_per_ray"] = max_nodes;
  if (cmd.settings.straggler_rays) {
    nlohmann::json per_pass = nlohmann::json::array(), worst = nlohmann::json::array();
    for (const auto& p : r.pass_stragglers) per_pass.push_back({{"max", p.max}, {"p9999", p.p9999}});
    // hex floats: the exact bits, so the ray replays as traced
    const auto hex = [](const glm::vec3& v) {
      return nlohmann::json::array({fmt::format("{:a}", v.x), fmt::format("{:a}", v.y), fmt::format("{:a}", v.z)});
    };
    for (const auto& w : r.worst_rays)
      worst.push_back({{"nodes", w.nodes}, {"org", hex(w.org)}, {"dir", hex(w.dir)},
                       {"tmin", fmt::format("{:a}", w.tmin)}, {"tmax", fmt::format("{:a}", w.tmax)}});
    j["stragglers"] = {{"rays", "extension rays of this device (rank 0's devices under MPI)"},
                       {"per_pass", per_pass}, {"worst", worst}};
  }
  j["image"] = {{"width", cmd.settings.width}, {"height", cmd.settings.height}, {"spp", r.samples},
                {"exr", out.exr.string()}, {"png", out.png.string()}};
  j["settings"] = {{"max_depth", cmd.settings.max_depth}, {"rr_depth", cmd.settings.rr_depth},
                   {"seed", cmd.settings.seed}, {"nee", cmd.settings.nee}, {"mis", cmd.settings.mis},
                   {"russian_roulette", cmd.settings.russian_roulette}};
  const auto& ts = prepared.tree.stats;
  j["scene_stats"] = {{"triangles", prepared.scene.triangle_count()}, {"dropped_triangles", ts.dropped_triangles},
                      {"emitters", prepared.tables.emitters.entries.size()},
                      {"punctual_lights", prepared.tables.punctual.lights.size()}};
  if (prepared.tables.environment) j["scene_stats"]["environment_map"] = prepared.tables.environment->source.string();
  j["kdtree"] = {{"depth", ts.depth}, {"nodes", ts.node_count}, {"leaves", ts.leaf_count},
                 {"average_leaf_triangles", ts.average_leaf_triangles}, {"sah_cost", ts.sah_cost},
                 {"bytes", ts.bytes}};
  const SceneMemory memory = scene_memory(prepared.tree, prepared.tables);
  const double kept = static_cast<double>(std::max<std::size_t>(prepared.tree.triangles.size(), 1));
  j["device_memory"] = {{"nodes", memory.nodes}, {"leaf_lists", memory.leaf_lists},
                        {"triangles", memory.triangles}, {"shading", memory.shading},
                        {"total", memory.total()}, {"bytes_per_triangle", static_cast<double>(memory.total()) / kept}};
  j["timings"] = {{"load_seconds", prepared.load_seconds}, {"build_seconds", ts.build_seconds},
                  {"compile_seconds", r.compile_seconds}, {"compile_from_cache", r.compile_from_cache},
                  {"render_seconds", r.render_seconds}};
  j["rays"] = r.rays;
  j["rays_per_second"] = r.render_seconds > 0 ? static_cast<double>(r.rays) / r.render_seconds : 0.0;
  j["samples_per_second"] =
      r.render_seconds > 0 ? double(r.samples) * cmd.settings.width * cmd.settings.height / r.render_seconds : 0.0;
  j["dropped_samples"] = r.dropped_samples;
  nlohmann::json kernels;
  for (const auto& [name, seconds] : r.kernel_seconds)
    kernels[name] = {{"seconds", seconds}, {"rays_per_second", seconds > 0 ? double(r.rays) / seconds : 0.0}};
  j["kernels"] = kernels;
  if (r.wavefront_size) {
    j["wavefront"] = {{"slots", r.wavefront_size}, {"bytes_per_path", r.path_state_bytes},
                      {"simd_efficiency", r.simd_efficiency}};
    if (!r.code_layout.empty())
      j["coherence"] = {{"code", r.code_layout}, {"pth_levels", r.pth_levels}, {"subtree_nodes", r.pth_subtree_nodes},
                        {"speculative", r.speculative}};
    nlohmann::json bounces = nlohmann::json::array();
    for (const auto& it : r.iterations)
      bounces.push_back({{"live_paths", it.live_paths}, {"extension_rays", it.live_paths},
                         {"shadow_rays", it.shadow_rays},
                         {"simd_efficiency", it.simd_groups ? it.simd_efficiency_sum / double(it.simd_groups) : 0.0},
                         {"kernel_seconds", it.kernel_seconds}});
    j["bounces"] = bounces;
  }
  return j;
}

// What decides the image: a checkpoint may only be resumed by a render that would produce it.
std::uint64_t render_fingerprint(const RenderCommand& cmd, const PreparedScene& p) {
  const auto& s = cmd.settings;
  const auto& c = p.camera;
  const std::string text = fmt::format(
      "{}|{}x{}|seed {}|depth {} rr {}|nee {} mis {} rr {}|env {}|eye {} {} {}|target {} {} {}|fov {}|tris {}",
      std::filesystem::weakly_canonical(cmd.scene).string(), s.width, s.height, s.seed, s.max_depth, s.rr_depth, s.nee,
      s.mis, s.russian_roulette, s.environment ? fmt::format("{} {} {}", s.environment->x, s.environment->y,
                                                               s.environment->z)
                                               : "none",
      c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.vfov_degrees, p.tree.triangles.size());
  // an environment map is named by its file (older checkpoints, without one, keep their fingerprint)
  if (p.tables.environment)
    return fnv1a64(text + "|envmap " + std::filesystem::weakly_canonical(p.tables.environment->source).string());
  return fnv1a64(text);
}

// The render of one process: alone, or one rank of an MPI job when `mpi` is given.
int render_job(const RenderCommand& cmd_in, [[maybe_unused]] const MpiSession* mpi) {
  RenderCommand cmd = cmd_in;
  std::tie(cmd.settings.width, cmd.settings.height) = parse_resolution(cmd.resolution);
  const bool env_map = is_environment_map_path(cmd.environment);
  if (!cmd.environment.empty() && !env_map) cmd.settings.environment = parse_rgb("--env", cmd.environment);
  if (cmd.settings.spp == 0 && cmd.settings.time_limit <= 0)
    throw InputError("--spp 0 needs --time SECONDS to say when to stop");
  if (cmd.settings.straggler_rays && !find_method(cmd.settings.method).wavefront)
    throw InputError(fmt::format("--stragglers reads the rays of a wavefront method's extension launches; --method {} "
                                 "has none (every method traces the same rays: use --method wavefront)",
                                 cmd.settings.method));
  if (cmd.settings.straggler_rays && cmd.stats_file.empty())
    throw InputError("--stragglers writes its rays to the --stats file: give --stats FILE.json");
#ifdef COHORT_HAVE_MPI
  const int rank = mpi ? mpi->rank() : 0;
  const int local_rank = mpi ? mpi->local_rank() : 0;
  const std::string host = mpi ? mpi->host() : this_host();
#else
  const int rank = 0, local_rank = 0;
  const std::string host = this_host();
#endif
  // check where the outputs go before spending time on the render; only rank 0 writes
  const OutputPaths out = output_paths(rank == 0 ? cmd.output : std::string("unused"), cmd.scene);

  const auto memory_limit =
      cmd.memory_limit_mib > 0 ? static_cast<std::uint64_t>(cmd.memory_limit_mib * 1048576.0) : std::uint64_t(0);
  const Backend backend = parse_backend(cmd.backend);
  std::vector<DeviceInfo> devices;
  DeviceOpener open_devices;
  if (backend == Backend::opencl) {
    devices = select_devices(list_backend_devices(backend), cmd.device, local_rank);
    if (memory_limit) {
      for (auto& device : devices) {
        device.global_memory = std::min(device.global_memory, memory_limit);
        device.max_allocation = std::min(device.max_allocation, memory_limit);
      }
    }
    open_devices = opencl_opener(devices);
  } else {
    // CUDA renders on one GPU per process (several through MPI ranks); opened here once so a
    // missing GPU is an error before the scene loads, and again on the worker thread that uses it
    devices.push_back(open_device(backend, cmd.device, memory_limit)->info());
    open_devices = [backend, spec = cmd.device, memory_limit](std::size_t) {
      return open_device(backend, spec, memory_limit);
    };
  }
  PreparedScene prepared = prepare_scene(cmd.scene);
  if (cmd.tree_budget_mib > 0)
    prepared.tree = build_kdtree_within(prepared.scene.positions, {},
                                        static_cast<std::size_t>(cmd.tree_budget_mib * 1048576.0));
  if (memory_limit) fit_scene_to(prepared, memory_limit);
  if (env_map) set_environment_map(prepared.tables, load_environment_map(cmd.environment));
  if (cmd.white_sky) apply_white_sky(prepared, cmd.settings);
  if (!cmd.camera_bounds.empty())
    prepared.camera = camera_from_bounds(prepared.scene.bounds(), parse_six("--camera-bounds", cmd.camera_bounds),
                                         prepared.camera.vfov_degrees);
  if (cmd.fov > 0) prepared.camera.vfov_degrees = cmd.fov;
  if (rank == 0) {
    for (const auto& w : prepared.scene.warnings) fmt::print(stderr, "warning: {}: {}\n", cmd.scene.string(), w);
    if (prepared.tree.stats.dropped_triangles)
      fmt::print(stderr, "warning: {}: dropped {} degenerate or non-finite triangles\n", cmd.scene.string(),
                 prepared.tree.stats.dropped_triangles);
  }

  const ProgramCache cache(cmd.no_cache ? std::nullopt : std::optional(ProgramCache::default_directory()));
  const std::size_t pixels = std::size_t(cmd.settings.width) * cmd.settings.height;
  const InterruptGuard interrupt;  // on every rank: rank 0 decides when to stop, the others finish their passes
#ifdef COHORT_HAVE_MPI
  if (rank != 0) {
    AssignedPasses passes(devices.size());
    DeviceWorkers workers(devices, open_devices, cache, prepared, cmd.settings, passes);
    try {
      run_assigned_passes(passes, pixels);
    } catch (...) {
      passes.abort();
      throw;
    }
    mpi->gather(rank_json(rank, host, prepared, workers.join()).dump());
    return 0;
  }
#endif

  const std::uint64_t fingerprint = render_fingerprint(cmd, prepared);
  RenderControl control;
  if (cmd.resume) control.resume_from = load_checkpoint(out.checkpoint, fingerprint);
  if (control.resume_from) fmt::print("resuming {} at {} spp\n", out.checkpoint.string(), control.resume_from->samples);
  if (cmd.checkpoint || cmd.resume) {
    control.checkpoint_seconds = cmd.checkpoint_seconds;
    control.checkpoint = [&](const FilmState& film) { save_checkpoint(out.checkpoint, fingerprint, film); };
  }
  control.stop_requested = [&] { return interrupt.requested(); };
  ProgressReporter reporter(stderr);
#ifdef COHORT_HAVE_MPI
  const std::size_t ranks = mpi ? static_cast<std::size_t>(mpi->size()) : 1;
#else
  const std::size_t ranks = 1;
#endif
  PassJob job(cmd.settings, [&](const Progress& p) { reporter.update(p); }, control,
              pass_window(devices.size() * ranks, pixels * sizeof(co_float4)), devices.size());
  if (ranks > 1) job.combine_on_host();  // other ranks send partial films
  std::vector<DeviceRun> runs;
  {
    DeviceWorkers workers(devices, open_devices, cache, prepared, cmd.settings, job);
#ifdef COHORT_HAVE_MPI
    if (mpi) {
      try {
        serve_passes(*mpi, job, pixels);
      } catch (...) {
        job.abort();
        throw;
      }
    }
#endif
    runs = workers.join();
  }
  const FilmState film = job.finish();
  reporter.finish();
  RenderResult result = merge_device_results(runs);
  result.image = film_image(film);
  result.samples = film.samples;
  result.resumed_samples = job.resumed_samples();
  result.dropped_samples = film.dropped_samples;
  result.interrupted = job.interrupted();
  result.render_seconds = job.seconds();
  result.rays = job.rays();  // every rank's rays

  nlohmann::json rank_figures = nlohmann::json::array();
  rank_figures.push_back(rank_json(0, host, prepared, runs));
#ifdef COHORT_HAVE_MPI
  if (mpi) {
    const auto texts = mpi->gather(rank_figures[0].dump());
    for (std::size_t r = 1; r < texts.size(); ++r) rank_figures.push_back(nlohmann::json::parse(texts[r]));
  }
#endif

  std::size_t device_count = 0;
  result.passes = 0;
  for (const auto& rank_entry : rank_figures)
    for (const auto& d : rank_entry["devices"]) {
      ++device_count;
      result.passes += d["passes"].get<std::uint32_t>();
    }

  write_exr(out.exr, result.image);
  write_png(out.png, result.image);
  const double mrays = result.render_seconds > 0 ? double(result.rays) / result.render_seconds * 1e-6 : 0;
  if (cmd.verbose) {
    const auto& ts = prepared.tree.stats;
    for (const auto& rank_entry : rank_figures)
      for (const auto& d : rank_entry["devices"])
        fmt::print("device{}: {} ({}): {} passes, {:.3f}s busy, {:.2f} Mrays/s\n",
                   ranks > 1 ? fmt::format(" (rank {})", rank_entry["rank"].get<int>()) : std::string(),
                   d["name"].get<std::string>(), d["platform"].get<std::string>(), d["passes"].get<std::uint32_t>(),
                   d["busy_seconds"].get<double>(), d["rays_per_second"].get<double>() * 1e-6);
    fmt::print("scene: {} triangles, {} emissive, {} punctual lights, loaded in {:.3f}s\n",
               prepared.scene.triangle_count(), prepared.tables.emitters.entries.size(),
               prepared.tables.punctual.lights.size(), prepared.load_seconds);
    if (prepared.tables.environment)
      fmt::print("environment map: {}, {}x{}\n", prepared.tables.environment->source.string(),
                 prepared.tables.environment->width, prepared.tables.environment->height);
    fmt::print("kd-tree: depth {}, {} nodes, {} leaves, {:.2f} triangles per leaf, SAH cost {:.2f}, built in {:.3f}s\n",
               ts.depth, ts.node_count, ts.leaf_count, ts.average_leaf_triangles, ts.sah_cost, ts.build_seconds);
    fmt::print("device memory: {}\n",
               describe(scene_memory(prepared.tree, prepared.tables), prepared.tree.triangles.size()));
    fmt::print("kernel compile: {:.3f}s ({})\n", result.compile_seconds, result.compile_from_cache ? "warm, from cache" : "cold");
    const auto features = prepared.tables.features.names();
    fmt::print("kernel features: {}\n", features.empty() ? std::string("none (Lambertian only)")
                                                         : fmt::format("{}", fmt::join(features, " ")));
    fmt::print("passes: {} of {} spp\n", result.passes, film.pass_samples);
    for (const auto& [name, seconds] : result.kernel_seconds) fmt::print("kernel {}: {:.3f}s\n", name, seconds);
    if (result.wavefront_size)
      fmt::print("wavefront: {} path slots x {} bytes = {:.1f} MiB, {} bounces, SIMD efficiency {:.3f}\n",
                 result.wavefront_size, result.path_state_bytes,
                 result.wavefront_size * result.path_state_bytes / 1048576.0, result.iterations.size(),
                 result.simd_efficiency);
    if (!result.code_layout.empty())
      fmt::print("coherence code: {}; PTH subtree {} levels, {} nodes\n", result.code_layout, result.pth_levels,
                 result.pth_subtree_nodes);
  }
  if (result.dropped_samples)
    fmt::print(stderr, "warning: {} NaN or infinite samples were dropped\n", result.dropped_samples);
  fmt::print("rendered {}x{} at {} spp in {:.2f}s ({:.2f} Mrays/s{})\n", cmd.settings.width, cmd.settings.height,
             result.samples, result.render_seconds, mrays,
             device_count > 1 ? fmt::format(", {} devices in {} rank{}", device_count, ranks, ranks > 1 ? "s" : "")
                              : std::string());
  fmt::print("wrote {}\nwrote {}\n", out.exr.string(), out.png.string());
  if (cmd.checkpoint || cmd.resume) fmt::print("wrote {}\n", out.checkpoint.string());
  if (!cmd.stats_file.empty()) {
    write_file_atomically(cmd.stats_file, stats_json(cmd, rank_figures, prepared, result, out, job.image_mean()).dump(2) + "\n");
    fmt::print("wrote {}\n", cmd.stats_file);
  }
  if (result.interrupted) {
    fmt::print(stderr, "interrupted by signal {} at {} spp: the image so far is saved{}\n", interrupt.signal_number(),
               result.samples, cmd.checkpoint || cmd.resume ? "; --resume continues it" : "");
    return 128 + interrupt.signal_number();
  }
  return 0;
}

}  // namespace

int run_render(const RenderCommand& cmd) {
#ifdef COHORT_HAVE_MPI
  if (MpiSession::launched_by_mpi()) {
    const MpiSession mpi;
    if (mpi.size() > 1) {
      // a failing rank ends the whole job with its rank and host, never leaves the others waiting
      try {
        return render_job(cmd, &mpi);
      } catch (const InputError& e) {
        mpi.abort(e.what(), 2);
      } catch (const std::exception& e) {
        mpi.abort(e.what(), 1);
      }
    }
    return render_job(cmd, nullptr);
  }
#endif
  return render_job(cmd, nullptr);
}

}  // namespace cohort
