/* Counter-based random numbers: every value is a hash of (seed, pixel, sample, segment, purpose,
 * draw), never of work-item order, so a path is the same whichever kernel or method traces it. */
#ifndef COHORT_RNG_H
#define COHORT_RNG_H

#include "common/core/port.h"

/* PCG-RXS-M-XS hash, as in docs/bench-protocol.md (Jarzynski & Olano, JCGT 2020). */
CO_INLINE uint32_t pcg_hash(uint32_t v) {
  uint32_t s = v * 747796405u + 2891336453u;
  uint32_t w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  return (w >> 22u) ^ w;
}

/* What a stream of numbers is used for; each purpose gets its own stream at every segment. */
#define RNG_CAMERA 0u
#define RNG_LIGHT 1u
#define RNG_BSDF 2u
#define RNG_ROULETTE 3u
#define RNG_ALPHA 4u         /* the segment's ray through BLEND surfaces (alpha.h) */
#define RNG_ALPHA_SHADOW 5u  /* the segment's shadow ray through them */

typedef struct Rng {
  uint32_t state;
} Rng;

/* A stream's state is pcg_hash of (seed, pixel, sample), chained one after the other, then of
 * segment * 16 + purpose. The first part depends on the path alone and the path's streams differ
 * only in the second, so a kernel that follows one path through its segments hashes the first once
 * (rng_path_key) and makes each stream with one hash more (rng_at). */
CO_INLINE uint32_t rng_path_key(uint32_t seed, uint32_t pixel, uint32_t sample) {
  uint32_t h = pcg_hash(seed ^ 0x9e3779b9u);
  h = pcg_hash(h ^ pixel);
  return pcg_hash(h ^ sample);
}

CO_INLINE Rng rng_at(uint32_t path_key, uint32_t segment, uint32_t purpose) {
  Rng r;
  r.state = pcg_hash(path_key ^ (segment * 16u + purpose));
  return r;
}

/* Uniform in [0, 1): 24 bits so that the value is exact in float. */
CO_INLINE float rng_next(Rng* r) {
  r->state = pcg_hash(r->state);
  return (float)(r->state >> 8) * (1.0f / 16777216.0f);
}

#endif
