#include "runtime/cli/cli.h"

#include <exception>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "runtime/cli/commands.h"
#include "runtime/render/scene/prepared_scene.h"
#include "runtime/render/methods/methods.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

void add_render_options(CLI::App& cmd, RenderCommand& r) {
  cmd.add_option("scene", r.scene, "Scene file: .gltf, .glb, .obj, .ply (optionally .gz)")->required();
  cmd.add_option("-o,--output", r.output, "Output path: NAME, NAME.exr or NAME.png (both are written)");
  cmd.add_option("--spp", r.settings.spp,
                 "Samples per pixel (0 with --time: until the time is up); with --target-error, each pixel's most");
  cmd.add_option("--res", r.resolution, "Image size WxH")->default_val("512x512");
  cmd.add_option("--max-depth", r.settings.max_depth,
                 "Path segments, as Mitsuba's max_depth (1 = emitters seen directly); 0 = unbounded");
  cmd.add_option("--rr-depth", r.settings.rr_depth, "First segment where Russian roulette may end a path");
  cmd.add_option("--seed", r.settings.seed, "Random seed: the same seed gives the same image");
  cmd.add_option("--device", r.device,
                 "Device index or name substring (see `cohort devices`); several: all, all:NAME, a comma list, or "
                 "rank:NAME (under MPI, one matching device per rank of a machine)");
  cmd.add_option("--backend", r.backend, "Device backend: opencl or cuda (the same kernels either way)")
      ->check(CLI::IsMember({"opencl", "cuda"}));
  // auto by default: it renders with the fastest method on this scene and device, and its probe's
  // launches are part of the image (runtime/render/methods/auto.cpp)
  cmd.add_option("--method", r.settings.method, "Rendering method: " + fmt::format("{}", fmt::join(method_names(), ", ")))
      ->check(CLI::IsMember(method_names()))
      ->default_val("auto");
  cmd.add_option("--wavefront-size", r.settings.wavefront_size,
                 "Path slots of the wavefront methods (default: chosen from the device)");
  cmd.add_option("--code", r.settings.sort.code,
                 "Coherence code of hash/pth, most significant part first: origin:N, origin-uniform:N, end:N, pth:N, "
                 "dir:N (default: origin-first for hash, pth-32 for pth), or a preset: paper, hash, origin-first, "
                 "two-point, pth-32; its pth:N sets the levels pth walks; up to 32 bits sort as 32-bit keys");
  cmd.add_option("--pth-levels", r.settings.sort.pth_levels,
                 "KD-tree levels pth walks in local memory (default: 10, fewer if the tree or local memory is smaller)")
      ->check(CLI::Range(1, 16));
  cmd.add_option("--sort-from-bounce", r.settings.sort.sort_from_bounce,
                 "hash/pth sort the rays of this bounce and later ones (1: camera rays too); earlier bounces trace "
                 "unsorted (default 3: on the H200 the sort of bounces 1 and 2 costs more than their sorted traversal saves)")
      ->check(CLI::Range(1, 1000));
  cmd.add_option("--sort-payload", r.settings.sort.sort_payload,
                 "hash/pth: gather (copy each sorted ray and its traversal state to its sorted position, then "
                 "trace them contiguously) or indirect (trace through the permutation, the default: faster on the H200)")
      ->check(CLI::IsMember({"gather", "indirect"}));
  cmd.add_option("--stragglers", r.settings.straggler_rays,
                 "Wavefront methods: write the N extension rays that visited the most KD-tree nodes, and each "
                 "pass's maximum and 99.99th percentile, to --stats (a diagnostic; replay with cohort replay)")
      ->check(CLI::Range(1, 100000));
  cmd.add_flag("--speculative", r.settings.speculative,
               "hash/pth: speculative resumed traversal (leaf tests wait until the SIMD group agrees)");
  cmd.add_option("--pass-spp", r.settings.pass_samples,
                 "Samples per pixel in one pass, the unit devices and ranks share (default: 1-4 M samples a pass); "
                 "the image depends on it, never on the devices")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--time", r.settings.time_limit, "Stop after this many seconds of rendering")
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("--env", r.environment, "Environment: constant radiance R,G,B (or one value), or an equirectangular map FILE.exr");
  cmd.add_flag("--white-sky", r.white_sky,
               "Benchmark workload: albedo 0.5 everywhere, constant sky 1, protocol camera, 5 segments, no RR");
  cmd.add_option("--camera-bounds", r.camera_bounds,
                 "Camera at fractions of the scene bounds: ex,ey,ez,tx,ty,tz (eye, then target)");
  cmd.add_option("--fov", r.fov, "Vertical field of view in degrees")->check(CLI::Range(0.01f, 179.f));
  cmd.add_option("--checkpoint", r.checkpoint_seconds,
                 "Save the film to OUT.checkpoint every SECONDS (and at the end, or on SIGINT/SIGTERM)")
      ->check(CLI::PositiveNumber)
      ->each([&r](const std::string&) { r.checkpoint = true; });
  cmd.add_option("--memory-limit", r.memory_limit_mib,
                 "Use at most this many MiB of device memory (the KD-tree gets shallower when the scene would not fit)")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--tree", r.tree,
                 "What rays are traced through: bvh4 (a 4-wide BVH, the fastest on the H200; every method), bvh8 (a compressed 8-wide BVH for GPUs' incoherent rays; not with pth or hash), bvh8f (an "
                 "8-wide BVH with float planes, eight boxes per AVX step, the fastest on CPUs; not with pth or hash), deep "
                 "(the KD-tree for GPUs), compact (a KD-tree of 0.6x the nodes) or auto (bvh8f where every device is "
                 "a CPU and the method is not pth or hash, else bvh4; compact without a GPU and deep with one where a "
                 "KD-tree is needed); the image is the same with every tree")
      ->check(CLI::IsMember(tree_choices()));
  cmd.add_option("--tree-budget", r.tree_budget_mib,
                 "Lower the KD-tree depth limit until nodes, leaf lists and triangles fit in this many MiB")
      ->check(CLI::PositiveNumber);
  cmd.add_flag("--resume", r.resume, "Continue from OUT.checkpoint when it exists (same scene and settings)");
  cmd.add_option("--stats", r.stats_file, "Write the run's figures to this JSON file");
  cmd.add_flag("--no-nee", [&r](std::int64_t) { r.settings.nee = false; }, "Disable next-event estimation");
  cmd.add_flag("--no-mis", [&r](std::int64_t) { r.settings.mis = false; }, "NEE without multiple importance sampling");
  cmd.add_flag("--no-rr", [&r](std::int64_t) { r.settings.russian_roulette = false; }, "Disable Russian roulette");
  cmd.add_option("--aov", r.aov,
                 "First-hit AOVs as extra EXR channels: albedo (albedo.R/G/B), normal (N.X/Y/Z), depth (depth.Z)");
  cmd.add_flag("--denoise", r.denoise,
               "Also write OUT.denoised.exr and .png, denoised by Open Image Denoise guided by albedo and normal");
  cmd.add_option("--target-error", r.target_error,
                 "Adaptive sampling to an image relative RMS error of about E (mean over pixels of the relative "
                 "squared error, estimated from the samples' variance): 4x4 tiles get samples in proportion to "
                 "their noise, so noisy tiles end above E and clean ones below; --spp is then each pixel's most "
                 "(the image records each pixel's count)");
  cmd.add_flag("--no-cache", r.no_cache, "Do not read or write the kernel binary cache");
  cmd.add_flag("-v,--verbose", r.verbose, "Report compile times, tree statistics and kernel times");
}

// The shipped Cornell box: from the working directory (the repository root), else from the source
// tree this binary was built from.
std::filesystem::path default_bench_scene() {
  const std::filesystem::path rel = "scenes/cornell-box.gltf";
  return std::filesystem::exists(rel) ? rel : std::filesystem::path(COHORT_SOURCE_DIR) / rel;
}

void add_bench_options(CLI::App& cmd, BenchCommand& b) {
  cmd.add_option("scenes", b.scenes, "Scene files (default: the shipped Cornell box)");
  cmd.add_option("--res", b.resolution, "Path tracing: image side N (N x N)")->default_val("512");
  cmd.add_option("--trace-res", b.trace_resolution, "Protocol rays: image side N (N x N primary rays)")
      ->default_val("1024");
  cmd.add_option("--spp", b.spp, "Path tracing: samples per pixel")->check(CLI::Range(1, 1 << 20));
  cmd.add_option("--reps", b.reps, "Repetitions of every figure (median and best)")->check(CLI::Range(3, 1000));
  cmd.add_option("--methods", b.methods, "Comma list of methods, all, or none (traversal only)");
  cmd.add_option("--view", b.views, "Comma list: exterior (the protocol camera), interior (Crytek Sponza's view)");
  cmd.add_option("--camera-bounds", b.camera_bounds, "An extra view at fractions of the bounds: ex,ey,ez,tx,ty,tz");
  cmd.add_option("--fov", b.fov, "Vertical field of view of the extra view")->check(CLI::Range(0.01f, 179.f));
  cmd.add_option("--code", b.sort.code, "Coherence code of hash/pth (see render --code)");
  cmd.add_option("--pth-levels", b.sort.pth_levels, "Subtree levels of pth")->check(CLI::Range(1, 16));
  cmd.add_option("--sort-from-bounce", b.sort.sort_from_bounce, "First bounce hash/pth sort (see render --sort-from-bounce)")
      ->check(CLI::Range(1, 1000));
  cmd.add_option("--sort-payload", b.sort.sort_payload, "hash/pth: gather or indirect (see render --sort-payload)")
      ->check(CLI::IsMember({"gather", "indirect"}));
  cmd.add_option("--device", b.device, "Device index or name substring");
  cmd.add_option("--backend", b.backend, "Device backend: opencl or cuda (the same kernels either way)")
      ->check(CLI::IsMember({"opencl", "cuda"}));
  cmd.add_option("--tree", b.tree, "auto, deep, compact, bvh4, bvh8 or bvh8f (see render --tree)")
      ->check(CLI::IsMember(tree_choices()));
  cmd.add_option("--json", b.json, "Write every figure to this JSON file");
  cmd.add_flag("--no-traversal", b.no_traversal, "Skip the primary and diffuse traversal workloads");
  cmd.add_flag("--gate", b.gate,
               "Instead: trace each bounce's protocol rays (--trace-res) in several orders and time a device sort of "
               "each order's keys: where would sorting pay on this device and scene?");
  cmd.add_option("--bounces", b.bounces, "--gate: bounces to measure")->check(CLI::Range(1, 8));
}

}  // namespace

RenderCommand parse_render_arguments(const std::vector<std::string>& arguments) {
  CLI::App app{"cohort render", "render"};
  RenderCommand command;
  add_render_options(app, command);
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw InputError(e.what());
  }
  return command;
}

int run_cli(int argc, char** argv) {
  CLI::App app{"Cohort: a wavefront path tracer for OpenCL devices", "cohort"};
  app.set_version_flag("--version", "cohort 0.1.0");
  app.require_subcommand(1);

  RenderCommand render;
  auto* render_cmd = app.add_subcommand("render", "Render a scene to OpenEXR and PNG");
  add_render_options(*render_cmd, render);

  std::filesystem::path info_scene;
  std::string info_tree = "auto";
  auto* info_cmd = app.add_subcommand("info", "Print a scene's size, materials, lights, tree and device memory");
  info_cmd->add_option("scene", info_scene, "Scene file")->required();
  info_cmd->add_option("--tree", info_tree,
                       "What to build: auto (what a render builds on a GPU: the 4-wide BVH, the default), bvh4, bvh8 (the "
                       "compressed 8-wide BVH), bvh8f (the 8-wide BVH with float planes), deep or compact (the KD-trees), or all (each, with its bytes per "
                       "triangle)")
      ->check(CLI::IsMember({"auto", "bvh4", "bvh8", "bvh8f", "deep", "compact", "all"}));

  BenchCommand bench;
  auto* bench_cmd = app.add_subcommand("bench", "Measure rays/s (protocol rays) and path tracing per method");
  add_bench_options(*bench_cmd, bench);

  ExportCommand export_args;
  auto* export_cmd = app.add_subcommand("export", "Write a scene's world-space triangles as PLY (benchmark utility)");
  export_cmd->group("");  // hidden: used by scripts/bench
  export_cmd->add_option("scene", export_args.scene, "Scene file")->required();
  export_cmd->add_option("-o,--output", export_args.output, "Output .ply")->required();
  export_cmd->add_option("--subdivide", export_args.subdivide, "Midpoint subdivision levels (4x triangles each)")
      ->check(CLI::Range(0, 6));
  export_cmd->add_option("--copies", export_args.copies, "Copies side by side along z (odd: one in the middle)")
      ->check(CLI::Range(1, 64));

  auto* devices_cmd = app.add_subcommand("devices", "List OpenCL platforms and devices");

  ReplayCommand replay;
  auto* replay_cmd =
      app.add_subcommand("replay", "Trace the rays of a --stats file's \"stragglers\" on the host, as the kernels do");
  replay_cmd->add_option("scene", replay.scene, "The scene that was rendered")->required();
  replay_cmd->add_option("stats", replay.stats, "A --stats JSON file of a render with --stragglers")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every usage error exits 2 with CLI11's message
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    if (*render_cmd) return run_render(render);
    if (*bench_cmd) {
      if (bench.scenes.empty()) bench.scenes.push_back(default_bench_scene());
      return run_bench(bench);
    }
    if (*export_cmd) return run_export(export_args);
    if (*info_cmd) return run_info(info_scene, info_tree);
    if (*devices_cmd) return run_devices();
    if (*replay_cmd) return run_replay(replay);
  } catch (const InputError& e) {
    fmt::print(stderr, "cohort: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "cohort: {}\n", e.what());
    return 1;
  }
  return 2;
}

}  // namespace cohort
