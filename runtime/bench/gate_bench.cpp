#include "runtime/bench/gate_bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <random>

#include "kernels/common/accel/bvh4_path.h"
#include "kernels/common/pth/coherence.h"
#include "runtime/bench/protocol_rays.h"
#include "runtime/accel/host_traversal.h"
#include "runtime/bench/trace_bench.h"
#include "runtime/render/pth/coherence.h"
#include "runtime/sort/radix_sort.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

co_vec3 org_of(const RayIn& r) { return v3(r.origin.x, r.origin.y, r.origin.z); }
co_vec3 dir_of(const RayIn& r) { return v3(r.dir.x, r.dir.y, r.dir.z); }

// Keys of a --code layout (uniform origin grid: the host has no centroid quantiles here); the
// paper's PTH bits come from the same walk the kernel takes, over the whole node array: the
// KD-tree's (pth_walk), or with a BVH the lanes bvh4_walk goes on with (bvh4_path_bits): the keys
// the pth pipeline sorts by on that tree.
// `end_t`: each ray's distance estimate for an end part (one per ray), or the kernel's estimate
// when empty: the previous segment's length `previous_t` (bounce 2 on), else where the ray leaves
// the box.
std::vector<std::uint64_t> layout_keys(const std::string& layout, const PreparedScene& scene,
                                       std::span<const RayIn> rays, unsigned bounce, std::span<const float> previous_t,
                                       std::span<const float> end_t = {}) {
  const KdTree& tree = scene.tree;
  const CodeParams c = parse_code_layout(layout, 10, tree.bounds);
  const KdTreeView view = host_view(tree);
  if (scene.bvh8 || scene.bvh8f)
    throw InputError(fmt::format("--tree {}: the PTH gate's walk runs on the KD-tree or the 4-wide BVH",
                                 scene.tree_kind()));
  std::optional<Bvh4View> bvh;
  if (scene.bvh4) bvh = host_view(*scene.bvh4);
  std::vector<std::uint64_t> keys(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const co_vec3 o = org_of(rays[i]), d = dir_of(rays[i]);
    const co_vec3 inv = kd_inverse(d);
    std::uint32_t bits = 0;
    float t0 = 0, t1 = 0;
    const bool inside = kd_begin(&view, o, inv, 0.f, INFINITY, &t0, &t1);
    const float end = !end_t.empty() ? end_t[i] : estimated_end(bounce, bounce > 1 ? previous_t[i] : 0.f, t1);
    if (c.pth_levels && inside && bvh) {
      bits = bvh4_path_bits(&*bvh, o, d, c.pth_levels);
    } else if (c.pth_levels && inside) {
      KdStackEntry stack[KD_MAX_DEPTH];
      int sp = 0;
      std::uint32_t node = 0;
      bits = pth_walk(tree.nodes.data(), std::uint32_t(tree.nodes.size()), c.pth_levels, o, d, inv, &node, &t0, &t1,
                      stack, &sp);
    }
    keys[i] = coherence_code(&c, nullptr, o, d, bits, end);
  }
  return keys;
}

// The exact hit distances: an upper bound on what an estimate buys the two-point key (Meister et
// al. 2020); a miss ends where the ray leaves the scene box.
std::vector<float> exact_ends(const KdTree& tree, std::span<const RayIn> rays, std::span<const ProtocolHit> hits) {
  const KdTreeView view = host_view(tree);
  std::vector<float> t(rays.size(), 0.f);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    float t0, t1;
    if (hits[i].triangle != HIT_NONE) t[i] = hits[i].t;
    else if (kd_begin(&view, org_of(rays[i]), kd_inverse(dir_of(rays[i])), 0.f, INFINITY, &t0, &t1)) t[i] = t1;
  }
  return t;
}

std::vector<std::uint32_t> order_by(const std::vector<std::uint64_t>& keys) {
  std::vector<std::uint32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  return order;
}

// Median device time of sorting the (key, value) pairs by `key_bits` bits, as 32-bit keys where
// they fit.
double sort_ms(const Device& cl, RadixSort& sort64, RadixSort& sort32, const std::vector<std::uint64_t>& keys,
               unsigned key_bits, unsigned reps) {
  RadixSort& sort = key_bits <= 32 ? sort32 : sort64;
  std::vector<std::uint32_t> values(keys.size());
  std::iota(values.begin(), values.end(), 0u);
  std::vector<std::uint32_t> keys32;  // the low 32 bits, for the 32-bit sort only
  if (key_bits <= 32) keys32.assign(keys.begin(), keys.end());
  const void* key_data = key_bits <= 32 ? static_cast<const void*>(keys32.data()) : keys.data();
  RateFigure ms;
  for (unsigned r = 0; r < reps; ++r) {
    const DeviceBuffer k = cl.allocate("gate keys", keys.size() * sort.key_bytes(), key_data);
    const DeviceBuffer v = cl.allocate("gate values", values.size() * 4, values.data());
    std::map<std::string, double> seconds;
    sort.sort(k, v, std::uint32_t(keys.size()), key_bits, &seconds);
    double total = 0;
    for (const auto& [name, s] : seconds) total += s;
    ms.runs.push_back(total * 1e3);
  }
  return ms.median();
}

}  // namespace

std::vector<GateBounce> gate_bench(const Device& cl, const ProgramCache& cache, const PreparedScene& scene,
                                   const SceneCamera& camera, const GateOptions& options) {
  const KdTree& tree = scene.tree;
  TraceBench tracer(cl, cache, tree, scene.bvh());
  std::vector<RayIn> rays = protocol_primary_rays(camera, options.res);
  const float diag = scene.scene.bounds().diagonal();
  std::vector<GateBounce> out;
  std::vector<float> previous_t;  // each ray's previous segment length, from bounce 2 on
  // waves only shrink after bounce 1
  RadixSort sort64(cl, cache, std::uint32_t(rays.size()));
  RadixSort sort32(cl, cache, std::uint32_t(rays.size()), SortKey::bits32);
  for (unsigned bounce = 1; bounce <= options.bounces && !rays.empty(); ++bounce) {
    GateBounce b;
    b.bounce = bounce;
    b.rays = rays.size();
    const TraceFigures base = tracer.trace(rays, options.reps);
    b.orders.push_back({"generation", 0, base.rays_per_second, 0});
    struct Keyed {
      const char* name;
      std::vector<std::uint64_t> keys;
      unsigned bits;
    };
    std::vector<Keyed> keyed;
    auto keys = [&](const char* layout, std::span<const float> end_t = {}) {
      return layout_keys(layout, scene, rays, bounce, previous_t, end_t);
    };
    keyed.push_back({"origin-first", keys("origin-uniform:8,dir:4"), 32});
    keyed.push_back({"direction-first", keys("dir:4,origin-uniform:8"), 32});
    keyed.push_back({"paper", keys("origin-uniform:8,pth:10,dir:8"), 60});
    keyed.push_back({"pth-32", keys("origin-uniform:7,pth:4,dir:1"), 31});
    keyed.push_back({"two-point", keys("origin-uniform:5,end:5", exact_ends(tree, rays, base.closest)), 30});
    keyed.push_back({"two-point-estimate", keys("origin-uniform:5,end:5"), 30});
    std::vector<std::uint64_t> shuffled(rays.size());
    std::iota(shuffled.begin(), shuffled.end(), std::uint64_t(0));
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(bounce));
    keyed.push_back({"random", std::move(shuffled), 32});
    for (const Keyed& k : keyed) {
      const std::vector<std::uint32_t> order = order_by(k.keys);
      std::vector<RayIn> sorted(rays.size());
      for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = rays[order[i]];
      const TraceFigures f = tracer.trace(sorted, options.reps);
      for (std::size_t i = 0; i < order.size(); ++i)
        if (f.closest[i].triangle != base.closest[order[i]].triangle || f.closest[i].t != base.closest[order[i]].t)
          b.hits_agree = false;
      b.orders.push_back({k.name, k.bits, f.rays_per_second, sort_ms(cl, sort64, sort32, k.keys, k.bits, options.reps)});
    }
    out.push_back(std::move(b));
    // the next bounce: diffuse rays from this bounce's hits (generation order)
    rays = protocol_diffuse_rays(rays, base.closest, scene.scene.positions, diag);
    previous_t.clear();  // the next rays start at this bounce's hits, in order
    for (const ProtocolHit& h : base.closest)
      if (h.triangle != HIT_NONE) previous_t.push_back(h.t);
  }
  return out;
}

}  // namespace cohort
