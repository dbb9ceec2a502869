// The stages of a wavefront bounce (kernels/common/wavefront_kernels.h), one file each. A method
// (runtime/render/methods) runs them in order; ray_sort.h has the stages that replace `extend` when
// rays are sorted before traversal.
#pragma once

#include "runtime/render/stages/wavefront_loop.h"

namespace cohort {

// Free slots take the pass's next work items (new camera paths), while any are left.
void generate(WavefrontPass& pass);
// Closest hit of every live path's next ray, and the traversal's SIMD efficiency.
void extend(WavefrontPass& pass);
// Emission, light sample, Russian roulette and the next direction; then the shadow rays it queued.
void shade(WavefrontPass& pass);
// Finished paths hand in their radiance and free their slots; live ones are counted and, with
// Launches::compacted, compacted into the queue of the next bounce (stream compaction).
void finish(WavefrontPass& pass);

}  // namespace cohort
