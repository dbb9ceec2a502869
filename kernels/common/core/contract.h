/* The host-device contract: every constant, sentinel, limit, saved-state layout and per-slot size
 * that the kernels and the host runtime must agree on, declared once. The kernels include it as
 * plain C (OpenCL C, CUDA); the host includes it as C++ (runtime/render/stages, the pass driver)
 * and uses these definitions directly, so nothing here is mirrored by hand. Each kernel's
 * parameter list is declared once too, in kernel_params.h. */
#ifndef COHORT_CONTRACT_H
#define COHORT_CONTRACT_H

#include "common/core/path_slot.h"
#include "common/core/types.h"

/* ---- Sentinels ---------------------------------------------------------------------------- */
#define ITEM_NONE 0xffffffffu      /* path_item of a free path slot */
#define TRAVERSAL_DONE 0xffffffffu /* TraversalState.node of a ray pth_resume skips */

/* ---- Counters ------------------------------------------------------------------------------
 * The wavefront kernels' counters[] (one buffer per pool). The host zeroes it at the start of a
 * pass and reads it only every few bounces (wavefront_loop.cpp): queue lengths stay on the device,
 * launches cover the pool and their work items past the count leave at once. */
#define COUNTER_NEXT_ITEM 0   /* the next work item (pixel, sample) of the pass wf_generate hands out */
#define COUNTER_QUEUE 1       /* live slots (and the length of the compacted queue) */
#define COUNTER_SHADOW 2      /* shadow rays queued this bounce */
#define COUNTER_SIMD_SUM 3    /* sum over groups of 32 traced rays of mean / max nodes, in units of 1e-4 */
#define COUNTER_SIMD_GROUPS 4 /* groups of 32 traced rays */
#define COUNTER_MAX_STEPS 5   /* the most KD-tree nodes one ray visited (the straggler figure) */
#define COUNTER_SURVIVED 6    /* nonzero when a path lived on after the last bounce: no refill without regeneration */
#define COUNTER_ITEMS_HANDED 7 /* COUNTER_NEXT_ITEM as the last bounce ended: wf_generate's early test */
#define COUNTER_COUNT 8

/* After the counters, wf_end_bounce keeps one row of figures per bounce, in a ring of BOUNCE_ROWS
 * rows indexed by the bounce's number: the host reads them with the counters, at least once every
 * BOUNCE_ROWS bounces. */
#define BOUNCE_LIVE 0        /* paths traced (extension rays) */
#define BOUNCE_SHADOW 1      /* shadow rays */
#define BOUNCE_SIMD_SUM 2    /* COUNTER_SIMD_SUM of the bounce */
#define BOUNCE_SIMD_GROUPS 3 /* COUNTER_SIMD_GROUPS of the bounce */
#define BOUNCE_FIGURES 4
#define BOUNCE_ROWS 64u
#define COUNTER_WORDS (COUNTER_COUNT + BOUNCE_ROWS * BOUNCE_FIGURES)

/* The megakernel's counters[]: NAIVE_COUNTER_SLOTS copies, a 64-byte line apart, each work-group adding
 * to the copy of its group index modulo the slot count (the host sums the rays and takes the most of
 * the steps over the slots). One shared line, written by every work item of every core, cost the CPU
 * a line transfer per pixel and pass. */
#define NAIVE_COUNTER_RAYS 0      /* rays traced */
#define NAIVE_COUNTER_MAX_STEPS 1 /* the most KD-tree nodes one ray visited */
#define NAIVE_COUNTER_COUNT 2
#define NAIVE_COUNTER_STRIDE 16u  /* words from one slot to the next: a 64-byte line */
#define NAIVE_COUNTER_SLOTS 16u
#define NAIVE_COUNTER_WORDS (NAIVE_COUNTER_STRIDE * NAIVE_COUNTER_SLOTS)

/* ---- Limits ---------------------------------------------------------------------------------- */
#define PTH_MAX_LEVELS 16 /* the deepest subtree pth_walk_and_code walks (its private stack) */
#define FILM_WG 256       /* film_add: the most work items a group may have; the host launches a power of two */
#define SIMD_GROUP 32u    /* rays per group of the SIMD efficiency figure, and per speculative vote */

/* ---- Saved traversal state ---------------------------------------------------------------------
 * What pth_walk_and_code leaves per path slot for pth_resume: where the walk stopped and how deep
 * its stack is; the stack's entries are stored entry-major (entry k of every slot together). */
typedef struct CO_ALIGN(16) TraversalState {
  uint32_t node; /* the node to continue from, or TRAVERSAL_DONE */
  float tmin, tmax;
  uint32_t depth; /* saved stack entries */
} TraversalState;
CO_STATIC_ASSERT(sizeof(TraversalState) == 16, "TraversalState must stay 16 bytes");

CO_INLINE TraversalState traversal_done(void) {
  TraversalState s;
  s.node = TRAVERSAL_DONE;
  s.tmin = 0.0f;
  s.tmax = 0.0f;
  s.depth = 0u;
  return s;
}

typedef struct CO_ALIGN(16) SavedStackEntry {
  uint32_t node;
  float tmin, tmax;
  uint32_t pad;
} SavedStackEntry;
CO_STATIC_ASSERT(sizeof(SavedStackEntry) == 16, "SavedStackEntry must stay 16 bytes");

/* ---- Device bytes per path slot ----------------------------------------------------------------
 * The path state (PATH_STATE_BYTES, path_slot.h); the hit; the shadow ray (origin, direction,
 * contribution); the shadow queue, the path queue and the nodes visited (uint each). */
#define SHADOW_RAY_BYTES (3u * 16u)
#define WAVEFRONT_SLOT_BYTES (PATH_STATE_BYTES + (uint32_t)sizeof(HitOut) + SHADOW_RAY_BYTES + 3u * 4u)
/* With a ray sort: key and value (twice, for the sort's ping-pong) and the traversal state; the
 * saved stack adds one SavedStackEntry per subtree level. */
#define SORT_SLOT_BYTES (2u * (8u + 4u) + (uint32_t)sizeof(TraversalState))
/* pth_gather's sorted copies per slot (--sort-payload gather): origin, direction, traversal state;
 * besides a second copy of the saved stack */
#define SORT_GATHER_SLOT_BYTES (2u * 16u + (uint32_t)sizeof(TraversalState))

#endif
