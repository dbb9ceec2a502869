#include "runtime/render/pth/sorted_traversal.h"

#include <fmt/format.h>

#include <algorithm>

#include "kernels/common/core/contract.h"
#include "runtime/render/stages/traversal_figures.h"
#include "runtime/util/error.h"

namespace cohort {

SortedTraversal::SortedTraversal(const WavefrontRender& render, RayOrder key)
    : key_(key),
      speculative_(render.inputs().settings.speculative),
      gather_(render.inputs().settings.sort.sort_payload == "gather"),
      sort_from_bounce_(render.inputs().settings.sort.sort_from_bounce) {
  const MethodInputs& in = render.inputs();
  const Device& cl = in.device;
  const std::uint32_t slots = render.pool().slots;
  if (in.scene.bvh8 || in.scene.bvh8f)
    throw InputError(fmt::format("--tree {}: the hash and pth methods walk the KD-tree or the 4-wide BVH; give --tree "
                                 "auto, bvh4, deep or compact with them",
                                 in.scene.bvh8 ? "bvh8" : "bvh8f"));
  if (speculative_ && in.scene.bvh4)
    throw InputError("--speculative is the KD-tree's resume: give --tree auto, deep or compact with it");
  program_ = cl.build_program(in.cache, "pth", in.scene.build_options);
  const bool pth = key == RayOrder::pth;
  // --code pth:N means N levels (docs/decisions.md): it and --pth-levels must agree when both are given
  const std::uint32_t requested = requested_pth_levels(in.settings.sort.code, in.settings.sort.pth_levels);
  subtree_ = pth ? choose_subtree(cl.info(), in.scene, requested) : SubtreeChoice{};
  layout_ = in.settings.sort.code.empty() ? default_code_layout(pth) : in.settings.sort.code;
  code_ = parse_code_layout(layout_, subtree_.levels, in.scene.bounds);
  if (!pth) code_.pth_levels = 0;  // the hash sort never walks the subtree
  if (code_.pth_levels > PTH_MAX_LEVELS) code_.pth_levels = PTH_MAX_LEVELS;
  // the walk pushes at most one cell per KD-tree level, three children per BVH level
  stack_entries_ = (in.scene.bvh4 ? 3 : 1) * code_.pth_levels;
  const std::size_t stack_bytes = std::size_t(slots) * sizeof(SavedStackEntry) * std::max<std::uint32_t>(stack_entries_, 1);
  code_params_ = cl.allocate("code parameters", sizeof(code_), &code_, Access::read_only);
  const auto bounds = origin_boundaries(in.scene, code_.origin_bits);
  origin_bounds_ = cl.allocate("origin grid", bounds.size() * sizeof(float), bounds.data(), Access::read_only);
  const SortKey width = code_.key_bits <= 32 ? SortKey::bits32 : SortKey::bits64;
  keys_ = cl.allocate("coherence codes", std::size_t(slots) * (width == SortKey::bits32 ? 4 : 8));
  values_ = cl.allocate("sorted slots", std::size_t(slots) * sizeof(std::uint32_t));
  traversal_ = cl.allocate("traversal states", std::size_t(slots) * sizeof(TraversalState));
  traversal_stack_ = cl.allocate("traversal stacks", stack_bytes);
  if (gather_) {
    sorted_org_ = cl.allocate("sorted ray origins", std::size_t(slots) * sizeof(co_float4));
    sorted_dir_ = cl.allocate("sorted ray directions", std::size_t(slots) * sizeof(co_float4));
    sorted_traversal_ = cl.allocate("sorted traversal states", std::size_t(slots) * sizeof(TraversalState));
    sorted_stack_ = cl.allocate("sorted traversal stacks", stack_bytes);
    gather_kernel_ = program_.kernel("pth_gather");
  }
  sort_.emplace(cl, in.cache, slots, width);
  walk_ = program_.kernel(width == SortKey::bits32 ? "pth_walk_and_code32" : "pth_walk_and_code");
  resume_ = program_.kernel(speculative_ ? "pth_resume_speculative" : "pth_resume");
}

// the loop counts bounces from 0; --sort-from-bounce from 1 (the camera rays)
bool SortedTraversal::sorts(const WavefrontPass& p) const { return p.bounce + 1 >= sort_from_bounce_; }

void SortedTraversal::walk(WavefrontPass& p) {
  const std::uint32_t count = p.count();
  const PathBuffers& path = p.pool.path;
  PthWalk w;
  w.params = p.buffers.params;
  w.scene = p.scene;
  w.path_org = path.path_org;
  w.path_dir = path.path_dir;
  w.path_item = path.path_item;
  w.path_segment = path.path_segment;
  w.path_status = path.path_status;
  w.queue = p.pool.queue;
  w.use_queue = p.use_queue();
  w.count = count;
  w.subtree_nodes = subtree_.nodes;
  w.code_params = code_params_;
  w.origin_bounds = origin_bounds_;
  w.values = values_;
  w.traversal = traversal_;
  w.traversal_stack = traversal_stack_;
  w.stack_stride = p.pool.slots;
  w.hits = p.pool.hits;
  w.counters = p.pool.counters;
  // the two walk kernels differ only in the width of their keys
  auto bind = [&](auto args) {
    args.walk = w;
    args.subtree = LocalMemory{std::max<std::size_t>(subtree_.local_bytes, sizeof(Bvh4Node))};
    args.keys = keys_;
    args.bind(walk_);
  };
  if (sort_->key() == SortKey::bits32) bind(PthWalkAndCode32Args{});
  else bind(PthWalkAndCodeArgs{});
  p.log.launch(p.device, walk_, key_ == RayOrder::pth ? "pth" : "hash", count);
}

void SortedTraversal::sort(WavefrontPass& p) {
  // the live count stays on the device: the sort reads it from the queue counter
  SortLaunches launches =
      sort_->sort_device_count_async(keys_, values_, p.count(), p.pool.counters, COUNTER_QUEUE, code_.key_bits);
  if (!launches.empty()) p.out.sort_launches += RadixSort::commands(code_.key_bits);  // with the fill
  for (auto& [name, event] : launches) p.log.add(name, std::move(event));
}

void SortedTraversal::resume(WavefrontPass& p) {
  const std::uint32_t count = p.count();
  if (gather_) {
    PthGatherArgs g;
    g.sorted_slots = values_;
    g.count = count;
    g.counters = p.pool.counters;
    g.use_queue = p.use_queue();
    g.path_org = p.pool.path.path_org;
    g.path_dir = p.pool.path.path_dir;
    g.traversal = traversal_;
    g.traversal_stack = traversal_stack_;
    g.stack_stride = p.pool.slots;
    g.sorted_org = sorted_org_;
    g.sorted_dir = sorted_dir_;
    g.sorted_traversal = sorted_traversal_;
    g.sorted_stack = sorted_stack_;
    g.bind(gather_kernel_);
    p.log.launch(p.device, gather_kernel_, "sort gather", count);  // the payload's share of the reorder
  }
  PthResumeArgs args;
  args.params = p.buffers.params;
  args.scene = p.scene;
  args.path_org = gather_ ? sorted_org_ : p.pool.path.path_org;
  args.path_dir = gather_ ? sorted_dir_ : p.pool.path.path_dir;
  args.sorted_slots = values_;
  args.count = count;
  args.traversal = gather_ ? sorted_traversal_ : traversal_;
  args.traversal_stack = gather_ ? sorted_stack_ : traversal_stack_;
  args.gathered = gather_ ? 1u : 0u;
  args.stack_stride = p.pool.slots;
  args.hits = p.pool.hits;
  args.steps = p.pool.steps;
  args.counters = p.pool.counters;
  args.use_queue = p.use_queue();
  args.bind(resume_);
  // the speculative kernel votes per work-group: make it one SIMD group
  p.log.launch(p.device, resume_, "resume", count, speculative_ ? SIMD_GROUP : 0);
  measure_traversal(p, &values_, count);
}

void SortedTraversal::report(RenderResult& result) const {
  result.compile_seconds += program_.seconds;
  result.compile_from_cache = result.compile_from_cache && program_.from_cache;
  result.wavefront.path_state_bytes += SORT_SLOT_BYTES + sizeof(SavedStackEntry) * stack_entries_;
  if (gather_) result.wavefront.path_state_bytes += SORT_GATHER_SLOT_BYTES + sizeof(SavedStackEntry) * stack_entries_;
  result.coherence = CoherenceFigures{.sort = {.code = layout_,
                                               .pth_levels = code_.pth_levels,
                                               .sort_from_bounce = sort_from_bounce_,
                                               .sort_payload = gather_ ? "gather" : "indirect"},
                                      .key_bits = code_.key_bits,
                                      .subtree_nodes = subtree_.nodes,
                                      .speculative = speculative_};
}

}  // namespace cohort
