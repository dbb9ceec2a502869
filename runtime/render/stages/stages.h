// The stages of a wavefront bounce (kernels/common/wavefront/wavefront_kernels.h), one file each. A method
// (runtime/render/methods) runs them in order; sorted_traversal.h has the stages that replace `extend` when
// rays are sorted before traversal.
#pragma once

#include "runtime/render/stages/wavefront_loop.h"

namespace cohort {

// When free slots take new paths: after every bounce (path regeneration), or only once every path
// of the pool has ended.
enum class Refill { every_bounce, when_drained };

// Free slots take the pass's next work items (new camera paths), while any are left.
void generate(WavefrontPass& pass, Refill refill);
// Closest hit of every live path's next ray, and the traversal's SIMD efficiency.
void extend(WavefrontPass& pass);
// Emission, light sample, Russian roulette and the next direction; then the shadow rays it queued.
void shade(WavefrontPass& pass);
// The bounce's figures into its row on the device; then finished paths hand in their radiance and
// free their slots, and live ones are counted and, with Launches::compacted, compacted into the
// queue of the next bounce (stream compaction).
void finish(WavefrontPass& pass);

}  // namespace cohort
