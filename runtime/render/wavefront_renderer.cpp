// The wavefront scheduler: a pool of path slots and one loop of small kernels per bounce
// (kernels/common/wavefront_kernels.h). `compact`, `regenerate` and the ray sort are the only differences
// between methods; with a sort, the extend stage becomes walk + code, device sort, and resumed
// traversal in sorted order (kernels/common/pth_kernels.h).
#include <algorithm>
#include <array>
#include <numeric>
#include <optional>

#include "runtime/render/coherence.h"
#include "runtime/render/launch_log.h"
#include "runtime/render/methods.h"
#include "runtime/render/pass_driver.h"
#include "runtime/sort/radix_sort.h"

namespace cohort {
namespace {

constexpr std::uint32_t kItemNone = 0xffffffffu;
// COUNTER_* of kernels/common/wavefront_path.h
enum Counter { kNextItem = 0, kQueue, kShadow, kSimdSum, kSimdGroups, kMaxSteps, kCounterCount };
// Source of the non-blocking counter resets: the host memory of a non-blocking write must outlive
// the command, so it cannot be a local of the loop.
constexpr std::array<std::uint32_t, kCounterCount> kZeros{};
constexpr std::uint32_t kPthMaxLevels = 16;  // PTH_MAX_LEVELS in kernels/common/pth_kernels.h

// Device bytes per slot: path state (5 float4 + 3 uint), hit, shadow ray (3 float4), two queues,
// traversal steps.
constexpr std::size_t kPathStateBytes = 5 * 16 + 3 * 4 + sizeof(HitOut) + 3 * 16 + 3 * 4;
// With a ray sort: key and value (twice, for the sort's ping-pong), traversal state.
constexpr std::size_t kSortBytes = 2 * (8 + 4) + 16;

// Enough paths in flight to fill the device: a few thousand per compute unit on a GPU, more on a
// CPU whose "compute units" are cores; never more than a quarter of the device memory.
std::uint32_t choose_pool_size(const Device& cl, const RenderSettings& s, std::uint64_t items,
                               std::size_t bytes_per_slot) {
  std::uint64_t slots = s.wavefront_size;
  if (slots == 0) {
    const std::uint64_t per_cu = cl.info().is_gpu ? 8192 : 32768;
    slots = std::clamp<std::uint64_t>(per_cu * cl.info().compute_units, 65536, 1u << 21);
    slots = std::min<std::uint64_t>(slots, cl.info().global_memory / 4 / bytes_per_slot);
  }
  slots = std::min<std::uint64_t>(slots, items);
  return static_cast<std::uint32_t>(std::max<std::uint64_t>(slots, 1));
}

struct Pool {
  std::uint32_t slots = 0;
  DeviceBuffer org, dir, throughput, radiance, prev, item, segment, status, hits, steps;
  DeviceBuffer shadow_org, shadow_dir, shadow_contribution, shadow_queue, queue, counters;

  Pool(const Device& cl, std::uint32_t n) : slots(n) {
    const std::size_t f4 = std::size_t(n) * 16, u = std::size_t(n) * 4;
    org = cl.allocate("path origins", f4);
    dir = cl.allocate("path directions", f4);
    throughput = cl.allocate("path throughput", f4);
    radiance = cl.allocate("path radiance", f4);
    prev = cl.allocate("path previous vertex", f4);
    const std::vector<std::uint32_t> free_slots(n, kItemNone);
    item = cl.allocate("path work items", u, free_slots.data());
    segment = cl.allocate("path segments", u);
    status = cl.allocate("path status", u);
    hits = cl.allocate("hits", std::size_t(n) * sizeof(HitOut));
    steps = cl.allocate("traversal steps", u);
    shadow_org = cl.allocate("shadow origins", f4);
    shadow_dir = cl.allocate("shadow directions", f4);
    shadow_contribution = cl.allocate("shadow contributions", f4);
    shadow_queue = cl.allocate("shadow queue", u);
    queue = cl.allocate("path queue", u);
    const std::array<std::uint32_t, kCounterCount> zero{};
    counters = cl.allocate("queue counters", sizeof(zero), zero.data());
  }
};

// What a sorting method adds: codes, the saved traversal states, the subtree and the sort.
struct SortStage {
  CodeParams code{};
  SubtreeChoice subtree;
  std::string layout;
  DeviceBuffer code_params, origin_bounds, keys, values, traversal, traversal_stack;
  std::optional<RadixSort> sort;
  DeviceKernel walk, resume;

  SortStage(const Device& cl, const ProgramCache& cache, const DeviceScene& scene, const Method& method,
            const RenderSettings& s, std::uint32_t slots) {
    const bool pth = method.sort == RaySort::pth;
    // --code pth:N means N levels (issue 25): it and --pth-levels must agree when both are given
    const std::uint32_t requested = requested_pth_levels(s.code, s.pth_levels);
    subtree = pth ? choose_subtree(cl.info(), scene, requested) : SubtreeChoice{};
    layout = s.code.empty() ? default_code_layout(pth) : s.code;
    code = parse_code_layout(layout, subtree.levels, scene.bounds);
    if (!pth) code.pth_levels = 0;  // the hash sort never walks the subtree
    if (code.pth_levels > kPthMaxLevels) code.pth_levels = kPthMaxLevels;
    code_params = cl.allocate("code parameters", sizeof(code), &code, Access::read_only);
    const auto bounds = origin_boundaries(scene, code.origin_bits);
    origin_bounds = cl.allocate("origin grid", bounds.size() * sizeof(float), bounds.data(), Access::read_only);
    keys = cl.allocate("coherence codes", std::size_t(slots) * 8);
    values = cl.allocate("sorted slots", std::size_t(slots) * 4);
    traversal = cl.allocate("traversal states", std::size_t(slots) * 16);
    traversal_stack = cl.allocate("traversal stacks", std::size_t(slots) * 16 * std::max<std::uint32_t>(code.pth_levels, 1));
    sort.emplace(cl, cache, slots);
  }
};

// The diagnostic of RenderSettings::straggler_rays: reads the nodes visited per launch index of an
// extension launch, and the rays of the worst `keep`. `slots`, when given, maps launch index to
// path slot (the compacted queue, or the sorted order).
void collect_stragglers(const Device& cl, const Pool& pool, const DeviceBuffer* slots, std::uint32_t count,
                        std::size_t keep, PassOutput& out) {
  std::vector<std::uint32_t> steps(count), slot_of(count);
  cl.read(pool.steps, 0, count * sizeof(std::uint32_t), steps.data());
  if (slots) cl.read(*slots, 0, count * sizeof(std::uint32_t), slot_of.data());
  else std::iota(slot_of.begin(), slot_of.end(), 0u);
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  const std::size_t worst = std::min<std::size_t>(keep, count);
  std::partial_sort(order.begin(), order.begin() + worst, order.end(),
                    [&](std::uint32_t a, std::uint32_t b) { return steps[a] > steps[b]; });
  std::vector<StragglerRay> rays;
  for (std::size_t k = 0; k < worst && steps[order[k]] > 0; ++k) {
    std::array<co_float4, 2> ray{};
    cl.read(pool.org, std::size_t(slot_of[order[k]]) * 16, 16, &ray[0]);
    cl.read(pool.dir, std::size_t(slot_of[order[k]]) * 16, 16, &ray[1]);
    rays.push_back({steps[order[k]], {ray[0].x, ray[0].y, ray[0].z}, {ray[1].x, ray[1].y, ray[1].z}});
  }
  keep_worst(out.worst_rays, std::move(rays), keep);
  for (std::uint32_t s : steps)
    if (s > 0) out.extension_steps.push_back(s);  // 0: a free or finished slot, not a ray
}

template <class Arg>
void set_arg(DeviceKernel& k, std::size_t& i, const Arg& arg) {
  k.set_arg(i++, arg);
}
// the scene stands for all the buffers of SCENE_KERNEL_PARAMS
void set_arg(DeviceKernel& k, std::size_t& i, const DeviceScene& scene) { i = set_scene_args(k, i, scene); }

template <class... Args>
void set_args(DeviceKernel& k, const Args&... args) {
  std::size_t i = 0;
  (set_arg(k, i, args), ...);
}

}  // namespace

RenderResult render_wavefront(const Method& method, const Device& cl, const ProgramCache& cache,
                              const DeviceScene& scene, const RenderParams& params, const RenderSettings& settings,
                              const ProgressCallback& progress, const RenderControl& control) {
  // the scene's feature options go to every program that shades or traces, so all methods compile
  // the shared code identically
  const DeviceProgram build = cl.build_program(cache, "wavefront", scene.build_options);
  const std::uint32_t pixels = settings.width * settings.height;
  // a launch holds one result per (pixel, sample): bound it to ~64 MiB of results, and to the
  // render's spp, which no launch exceeds (small renders then allocate little: Oclgrind's checks
  // cost time in proportion to the memory allocated, at every launch)
  std::uint32_t max_per_pass = std::max<std::uint32_t>(1, (1u << 22) / std::max<std::uint32_t>(pixels, 1));
  if (settings.spp > 0) max_per_pass = std::min(max_per_pass, settings.spp);
  const std::uint64_t max_items = std::uint64_t(pixels) * std::min(max_per_pass, std::max<std::uint32_t>(settings.spp, 1));
  const bool sorting = method.sort != RaySort::none;
  Pool pool(cl, choose_pool_size(cl, settings, max_items, kPathStateBytes + (sorting ? kSortBytes : 0)));
  DeviceBuffer results = cl.allocate("pass results", std::size_t(pixels) * max_per_pass * 16);
  const std::uint32_t use_queue = method.compact ? 1 : 0;

  DeviceKernel generate = build.kernel("wf_generate"), extend = build.kernel("wf_extend"),
               shade = build.kernel("wf_shade"), shadow = build.kernel("wf_shadow"),
               finish = build.kernel("wf_finish"), accumulate = build.kernel("wf_accumulate"),
               simd = build.kernel("wf_simd_efficiency"), shadow_max = build.kernel("wf_shadow_max_steps");
  std::optional<SortStage> sort_stage;
  std::optional<DeviceProgram> pth_build;
  if (sorting) {
    pth_build = cl.build_program(cache, "pth", scene.build_options);
    sort_stage.emplace(cl, cache, scene, method, settings, pool.slots);
    sort_stage->walk = pth_build->kernel("pth_walk_and_code");
    sort_stage->resume = pth_build->kernel(settings.speculative ? "pth_resume_speculative" : "pth_resume");
  }
  const auto& sc = scene;
  std::vector<IterationStats> iterations;

  auto pass = [&](const PassBuffers& b, const RenderParams& p) {
    const std::uint32_t items = pixels * p.samples_per_pass;
    const auto& [o, d, t, r, pv, it, sg, st] =
        std::tie(pool.org, pool.dir, pool.throughput, pool.radiance, pool.prev, pool.item, pool.segment, pool.status);
    set_args(generate, b.params, o, d, t, r, pv, it, sg, st, pool.counters, pool.queue, use_queue, pool.slots, items);
    set_args(finish, o, d, t, r, pv, it, sg, st, results, pool.counters, pool.queue, use_queue, pool.slots);
    set_args(shadow, b.params, sc, r, pool.shadow_org, pool.shadow_dir,
             pool.shadow_contribution, pool.shadow_queue, pool.counters, pool.steps);
    shadow_max.set_args(pool.steps, pool.counters);
    accumulate.set_args(b.params, results, b.film, b.dropped);

    std::array<std::uint32_t, kCounterCount> counters{};
    cl.write(pool.counters, 0, sizeof(kZeros), kZeros.data(), false);
    PassOutput out;
    LaunchLog log;
    std::map<std::string, double> sort_seconds;
    std::uint64_t remaining = items;
    std::uint32_t live = 0;
    for (std::size_t iteration = 0;; ++iteration) {
      // free slots take new paths: every bounce with regeneration, else only when the pool drained
      if (remaining > 0 && (method.regenerate || live == 0)) {
        log.launch(cl, generate, "generate", pool.slots);
        const std::uint64_t started = std::min<std::uint64_t>(pool.slots - live, remaining);
        remaining -= started;
        live += static_cast<std::uint32_t>(started);
      }
      if (live == 0) break;
      const std::uint32_t count = method.compact ? live : pool.slots;
      if (sort_stage) {
        SortStage& ss = *sort_stage;
        set_args(ss.walk, b.params, sc, o, d, it, st, pool.queue, use_queue, count,
                 LocalMemory{std::max<std::size_t>(ss.subtree.local_bytes, sizeof(KdNode))}, ss.subtree.nodes,
                 ss.code_params, ss.origin_bounds, ss.keys, ss.values, ss.traversal, ss.traversal_stack, pool.slots,
                 pool.hits);
        log.launch(cl, ss.walk, method.sort == RaySort::pth ? "pth" : "hash", count);
        ss.sort->sort(ss.keys, ss.values, count, ss.code.key_bits, &sort_seconds);
        set_args(ss.resume, b.params, sc, o, d, ss.values, count, ss.traversal,
                 ss.traversal_stack, pool.slots, pool.hits, pool.steps);
        // the speculative kernel votes per work-group: make it one SIMD group of 32
        log.launch(cl, ss.resume, "resume", count, settings.speculative ? 32 : 64);
        if (settings.straggler_rays) collect_stragglers(cl, pool, &ss.values, count, settings.straggler_rays, out);
      } else {
        set_args(extend, b.params, sc, o, d, t, r, pv, it, sg, st, pool.hits,
                 pool.queue, use_queue, count, pool.steps);
        log.launch(cl, extend, "extend", count);
        if (settings.straggler_rays)
          collect_stragglers(cl, pool, use_queue ? &pool.queue : nullptr, count, settings.straggler_rays, out);
      }
      simd.set_args(pool.steps, count, pool.counters);
      log.launch(cl, simd, "simd efficiency", (count + 31) / 32);
      set_args(shade, b.params, sc, o, d, t, r, pv, it, sg, st, pool.hits, pool.queue,
               use_queue, count, pool.shadow_org, pool.shadow_dir, pool.shadow_contribution, pool.shadow_queue,
               pool.counters);
      log.launch(cl, shade, "shade", count);
      log.launch(cl, shadow, "shadow", live);  // at most one shadow ray per live path
      log.launch(cl, shadow_max, "simd efficiency", (live + 31) / 32);
      cl.write(pool.counters, kQueue * 4, 4, kZeros.data(), false);
      log.launch(cl, finish, "finish", pool.slots);
      cl.read(pool.counters, 0, sizeof(counters), counters.data());
      cl.write(pool.counters, kShadow * 4, 3 * 4, kZeros.data(), false);

      if (iterations.size() <= iteration) iterations.resize(iteration + 1);
      IterationStats& stats = iterations[iteration];
      stats.live_paths += live;
      stats.shadow_rays += counters[kShadow];
      stats.simd_groups += counters[kSimdGroups];
      stats.simd_efficiency_sum += counters[kSimdSum] * 1e-4;
      auto seconds = log.collect();
      add_seconds(seconds, sort_seconds);
      sort_seconds.clear();
      add_seconds(stats.kernel_seconds, seconds);
      add_seconds(out.kernel_seconds, seconds);
      out.rays += live + counters[kShadow];
      out.max_steps = std::max(out.max_steps, counters[kMaxSteps]);
      live = counters[kQueue];
    }
    log.launch(cl, accumulate, "accumulate", pixels);
    add_seconds(out.kernel_seconds, log.collect());
    return out;
  };
  RenderResult result = drive_passes(cl, cache, params, settings, max_per_pass, progress, control, pass);
  result.compile_seconds = build.seconds + (pth_build ? pth_build->seconds : 0);
  result.compile_from_cache = build.from_cache && (!pth_build || pth_build->from_cache);
  std::uint64_t groups = 0;
  double efficiency = 0;
  for (const auto& i : iterations) {
    groups += i.simd_groups;
    efficiency += i.simd_efficiency_sum;
  }
  result.simd_efficiency = groups ? efficiency / double(groups) : 0;
  result.iterations = std::move(iterations);
  result.wavefront_size = pool.slots;
  result.path_state_bytes = kPathStateBytes + (sorting ? kSortBytes + 16 * sort_stage->code.pth_levels : 0);
  if (sort_stage) {
    result.code_layout = sort_stage->layout;
    result.pth_levels = sort_stage->code.pth_levels;
    result.pth_subtree_nodes = sort_stage->subtree.nodes;
    result.speculative = settings.speculative;
  }
  return result;
}

}  // namespace cohort
