// The stages that replace `extend` when rays are sorted before traversal (kernels/common/
// pth_kernels.h): walk (the top levels of the tree the scene was uploaded with, the 4-wide BVH or
// the KD-tree, in local memory, then the coherence code), sort (the
// device radix sort of (code, slot) pairs) and resume (each traversal continues, in sorted order,
// from the state the walk saved). With the hash key the walk covers no levels: the hash sort of
// Garanzha & Loop. Layouts of at most 32 bits are sorted as 32-bit keys (half the sort's traffic).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "runtime/render/pth/coherence.h"
#include "runtime/render/stages/wavefront_loop.h"
#include "runtime/sort/radix_sort.h"

namespace cohort {

// What the sort key holds beyond the origin and direction.
enum class RayOrder {
  hash,  // origin and direction only (Garanzha & Loop 2010)
  pth,   // with the bits of the partial traversal of the top subtree (Wang & Deng)
};

class SortedTraversal {
 public:
  SortedTraversal(const WavefrontRender& render, RayOrder key);

  // Whether this bounce's rays are sorted (--sort-from-bounce); else the method traces them with
  // `extend` (the gate benchmark: camera rays in pixel order trace about as fast as any sorted
  // order, so their sort does not pay).
  bool sorts(const WavefrontPass& pass) const;
  void walk(WavefrontPass& pass);
  void sort(WavefrontPass& pass);
  void resume(WavefrontPass& pass);
  // The code, the subtree and the compile time into the render's figures.
  void report(RenderResult& result) const;

 private:
  RayOrder key_;
  bool speculative_;
  bool gather_;  // --sort-payload gather
  std::uint32_t sort_from_bounce_;
  std::uint32_t stack_entries_ = 1;  // saved stack entries per slot
  DeviceProgram program_;
  CodeParams code_{};
  SubtreeChoice subtree_;
  std::string layout_;
  DeviceBuffer code_params_, origin_bounds_, keys_, values_, traversal_, traversal_stack_;
  // pth_gather's copies in sorted order (only with gather_)
  DeviceBuffer sorted_org_, sorted_dir_, sorted_traversal_, sorted_stack_;
  std::optional<RadixSort> sort_;
  DeviceKernel walk_, gather_kernel_, resume_;
};

}  // namespace cohort
