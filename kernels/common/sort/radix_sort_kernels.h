/* Stable LSD radix sort of (key, uint32_t value) pairs, keys of 32 or 64 bits, in plain OpenCL C 1.2:
 * one launch per digit of up to 8 bits, the "onesweep" shape of Adinets & Merrill, "Onesweep: A
 * Faster Least Significant Digit Radix Sort for GPUs" (2022). A sort of 32-bit keys is a fill, one
 * histogram launch and four digit passes; the reduce-then-scan sort it replaced took 40 launches.
 *
 *   sort_histogram  every digit of every pass is counted in one read of the keys into
 *                   hist[pass * 256 + digit] (global atomics once per work-group and bin); it also
 *                   clears the look-back table and the block tickets of every pass;
 *   sort_pass       one digit: each work-group takes the next tile by ticket (so tiles are handed
 *                   out in the order work-groups start), counts the tile's digits, publishes the
 *                   counts, and finds the tile's place among the pairs of earlier tiles with the same
 *                   digit by decoupled look-back (Merrill & Garland, "Single-pass Parallel Prefix Scan
 *                   with Decoupled Look-back", 2016): it adds the published counts of the tiles before
 *                   it, walking back until a tile that has published its inclusive prefix. Each
 *                   (tile, digit) word holds a flag in its two top bits (0: not yet, AGGREGATE: the
 *                   tile's own count, PREFIX: the count of this and every earlier tile) and a count
 *                   in the low 30 bits, written and read with 32-bit atomics, so no memory fence is
 *                   needed: the word is the whole message.
 *
 * Forward progress: a tile only waits for tiles with smaller tickets, and a ticket is taken by a
 * work-group that is already running, so the wait always ends, on GPUs (whose resident groups run
 * concurrently) and on CPU runtimes (each group runs to its end on one thread) alike.
 *
 * Stability: tiles are placed in ticket order, which is input order, and each tile is ranked
 * stably. With one work item per group (the CPU tiling, SORT_WG == 1) the item walks its tile in
 * order and writes each pair straight to its destination, the classic sequential counting-sort
 * pass. With a work-group (GPUs, SORT_LOCAL_EXCHANGE == 1) the tile is staged in local memory and
 * sorted there by the digit in two stable 4-bit steps (each item owns a contiguous run of the tile
 * and one counter per 4-bit value in its column of a value-major table; scanning that table in
 * (value, item) order gives each run's first rank), then written out in rank order so that
 * consecutive work items write consecutive addresses. Counters are only touched by their owner: no
 * sub-groups, nothing beyond OpenCL C 1.2. Every barrier is reached by the whole work-group.
 *
 * Compile-time sizes, chosen by the host from the device (runtime/sort/radix_sort.cpp):
 *   SORT_WG              work items per work-group: 1, or a power of two dividing 256;
 *   SORT_ITEMS           pairs per work item, so a tile has SORT_WG * SORT_ITEMS pairs;
 *   SORT_LOCAL_EXCHANGE  1: stage and rank tiles in local memory (required when SORT_WG > 1);
 *   SORT_KEY64           1: 64-bit keys, 0: 32-bit keys. */
#ifndef COHORT_RADIX_SORT_KERNELS_H
#define COHORT_RADIX_SORT_KERNELS_H

#include "common/core/port.h"

#if !defined(SORT_WG) || !defined(SORT_ITEMS) || !defined(SORT_LOCAL_EXCHANGE) || !defined(SORT_KEY64)
#error "SORT_WG, SORT_ITEMS, SORT_LOCAL_EXCHANGE and SORT_KEY64 must be defined by the host"
#endif
#if SORT_WG > 1 && !SORT_LOCAL_EXCHANGE
#error "work-groups of more than one item rank their tiles in local memory (SORT_LOCAL_EXCHANGE=1)"
#endif

#if SORT_KEY64
typedef uint64_t sort_key_t;
#else
typedef uint32_t sort_key_t;
#endif

#define SORT_BINS 256                 /* digit values of the widest (8-bit) digit */
#define SORT_MAX_PASSES 8             /* 64-bit keys in 8-bit digits */
#define TILE (SORT_WG * SORT_ITEMS)   /* pairs per work-group of sort_pass */
#define LOOKBACK_AGGREGATE 0x40000000u
#define LOOKBACK_PREFIX 0x80000000u
#define LOOKBACK_COUNT 0x3fffffffu
#define SORT_NO_COUNT_WORD 0xffffffffu /* count_index: the count is the argument itself */

/* The number of pairs: `count`, or at most `count` taken from count_word[count_index] when the
 * count lives on the device (a queue length the host never reads). */
CO_INLINE uint32_t sort_count(uint32_t count, CO_GLOBAL const uint32_t* count_word, uint32_t count_index) {
  return count_index == SORT_NO_COUNT_WORD ? count : co_umin(count, count_word[count_index]);
}

/* Local tables are scanned with each work item reading 16 consecutive entries; one padding word
 * every 32 keeps those strided reads free of bank conflicts on 32-bank GPUs (Harris, Sengupta &
 * Owens, GPU Gems 3, ch. 39). */
#define PAD(i) ((i) + ((i) >> 5))
#define TABLE_WORDS(entries) PAD(entries)

/* digit_mask is narrower than the pass's digit on the last pass when the key bits do not divide
 * evenly: bits above key_bits are then ignored, not sorted. */
CO_INLINE uint32_t key_digit(sort_key_t key, uint32_t shift, uint32_t digit_mask) {
  return (uint32_t)(key >> shift) & digit_mask;
}

/* Exclusive scan of one value per work item (Hillis & Steele, "Data Parallel Algorithms", 1986):
 * log2(group) steps over a local array. `group` is a compile-time constant at every call. Returns
 * the exclusive prefix; *total gets the sum over the work-group. */
CO_INLINE uint32_t group_exclusive_scan(uint32_t x, CO_LOCAL uint32_t* tmp, uint32_t* total, const uint32_t group) {
  const uint32_t item = co_local_id();
  tmp[item] = x;
  co_barrier();
  for (uint32_t offset = 1; offset < group; offset <<= 1) {
    const uint32_t y = item >= offset ? tmp[item - offset] : 0u;
    co_barrier();
    tmp[item] += y;
    co_barrier();
  }
  const uint32_t inclusive = tmp[item];
  *total = tmp[group - 1];
  co_barrier(); /* tmp may be reused by the caller */
  return inclusive - x;
}

/* In-place exclusive scan of the per_item * group entries of `table` (linear index i stored at
 * PAD(i)), Blelloch's three phases ("Prefix Sums and Their Applications", 1990): each work item
 * reduces its per_item consecutive entries, the sums are scanned across the work-group, and each
 * item rewrites its entries from its offset. The caller must have passed a barrier after filling
 * the table; the scanned table is visible to every work item on return. */
CO_INLINE void scan_table(CO_LOCAL uint32_t* table, CO_LOCAL uint32_t* tmp, const uint32_t group,
                          const uint32_t per_item) {
  const uint32_t first = co_local_id() * per_item;
  uint32_t sum = 0;
  for (uint32_t i = 0; i < per_item; ++i) sum += table[PAD(first + i)];
  uint32_t total;
  uint32_t offset = group_exclusive_scan(sum, tmp, &total, group);
  for (uint32_t i = 0; i < per_item; ++i) {
    const uint32_t slot = PAD(first + i);
    const uint32_t count = table[slot];
    table[slot] = offset;
    offset += count;
  }
  co_barrier();
}

/* hist[pass * 256 + d] += number of keys whose digit of that pass is d, over this work-group's
 * share of the keys (the launch has `groups` work-groups); the host has zeroed hist. Also zeroes
 * the look-back words of every pass that sort_pass will use (pass p's table starts at word
 * p * tile_stride * 256) and tickets[0, passes): sort_pass relies on both. */
CO_KERNEL_WG(SORT_WG)
sort_histogram(CO_GLOBAL const sort_key_t* keys, uint32_t count, CO_GLOBAL const uint32_t* count_word,
               uint32_t count_index, uint32_t groups, uint32_t passes, uint32_t digit_bits, uint32_t key_bits,
               CO_GLOBAL uint32_t* hist, CO_GLOBAL uint32_t* lookback, uint32_t tile_stride,
               CO_GLOBAL uint32_t* tickets) {
  CO_SHARED uint32_t bins[SORT_MAX_PASSES * SORT_BINS];
  const uint32_t item = co_local_id();
  const uint32_t n = sort_count(count, count_word, count_index);
  const uint32_t used = (n + TILE - 1) / TILE * SORT_BINS; /* look-back words per pass */
  for (uint32_t p = 0; p < passes; ++p)
    for (uint32_t i = co_global_id(); i < used; i += groups * SORT_WG) lookback[p * tile_stride * SORT_BINS + i] = 0u;
  if (co_group_id() == 0)
    for (uint32_t p = item; p < passes; p += SORT_WG) tickets[p] = 0u;

  const uint32_t bins_used = passes * SORT_BINS;
  for (uint32_t i = item; i < bins_used; i += SORT_WG) bins[i] = 0u;
  co_barrier();
  /* Each group counts a contiguous chunk; consecutive items read consecutive keys. */
  const uint32_t chunk = (n + groups - 1) / groups;
  const uint32_t begin = co_umin(n, co_group_id() * chunk);
  const uint32_t end = co_umin(n, begin + chunk);
  for (uint32_t j = begin + item; j < end; j += SORT_WG) {
    const sort_key_t key = keys[j];
    for (uint32_t p = 0; p < passes; ++p) {
      const uint32_t shift = p * digit_bits;
      const uint32_t bits = shift < key_bits ? co_umin(digit_bits, key_bits - shift) : 0u;
      const uint32_t d = key_digit(key, shift, (1u << bits) - 1u);
#if SORT_WG > 1
      co_atomic_inc(&bins[p * SORT_BINS + d]);
#else
      bins[p * SORT_BINS + d] += 1u;
#endif
    }
  }
  co_barrier();
  for (uint32_t i = item; i < bins_used; i += SORT_WG)
    if (bins[i] != 0u) co_atomic_add(&hist[i], bins[i]);
}

#if SORT_LOCAL_EXCHANGE
/* One stable ranking step of the local tile by the 4-bit value (digit >> nibble_shift) & 15: each
 * item takes its run, counts it into its column, the table is scanned, and the run is written back
 * at its ranks. */
CO_INLINE void rank_tile_by_nibble(CO_LOCAL sort_key_t* tile_keys, CO_LOCAL uint32_t* tile_values,
                                   CO_LOCAL uint32_t* table, CO_LOCAL uint32_t* tmp, uint32_t n, uint32_t shift,
                                   uint32_t digit_mask, uint32_t nibble_shift) {
  const uint32_t item = co_local_id();
  const uint32_t run = item * SORT_ITEMS;
  sort_key_t keys[SORT_ITEMS];
  uint32_t values[SORT_ITEMS];
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    keys[i] = run + i < n ? tile_keys[run + i] : (sort_key_t)0;
    values[i] = run + i < n ? tile_values[run + i] : 0u;
  }
  for (uint32_t v = 0; v < 16; ++v) table[PAD(v * SORT_WG + item)] = 0u;
  for (uint32_t i = 0; i < SORT_ITEMS; ++i)
    if (run + i < n) table[PAD(((key_digit(keys[i], shift, digit_mask) >> nibble_shift) & 15u) * SORT_WG + item)] += 1u;
  co_barrier(); /* also: every item has read its run before the tile is overwritten */
  scan_table(table, tmp, SORT_WG, 16);
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    if (run + i < n) {
      const uint32_t slot = PAD(((key_digit(keys[i], shift, digit_mask) >> nibble_shift) & 15u) * SORT_WG + item);
      const uint32_t rank = table[slot];
      table[slot] = rank + 1u;
      tile_keys[rank] = keys[i];
      tile_values[rank] = values[i];
    }
  }
  co_barrier();
}
#endif

/* Digit pass `pass` of a sort: moves every pair to its place by the digit at bits [shift, shift +
 * bits of digit_mask). It uses the pass's 256 digit counts over all keys in `hist`, its look-back
 * table from word pass * tile_stride * 256 and its tile counter in `tickets`, all zeroed by
 * sort_histogram. Launched over as many tiles as the count may need: groups whose ticket is past
 * the last tile of the actual count leave at once. */
CO_KERNEL_WG(SORT_WG)
sort_pass(CO_GLOBAL const sort_key_t* keys_in, CO_GLOBAL const uint32_t* values_in, CO_GLOBAL sort_key_t* keys_out,
          CO_GLOBAL uint32_t* values_out, uint32_t max_count, CO_GLOBAL const uint32_t* count_word,
          uint32_t count_index, uint32_t shift, uint32_t digit_mask, uint32_t pass, uint32_t tile_stride,
          CO_GLOBAL const uint32_t* all_hist, CO_GLOBAL uint32_t* all_lookback, CO_GLOBAL uint32_t* tickets) {
  CO_GLOBAL const uint32_t* hist = all_hist + pass * SORT_BINS;
  CO_GLOBAL uint32_t* lookback = all_lookback + pass * tile_stride * SORT_BINS;
  CO_GLOBAL uint32_t* ticket = tickets + pass;
  const uint32_t count = sort_count(max_count, count_word, count_index);
  CO_SHARED uint32_t tile_index;
  CO_SHARED uint32_t counts[SORT_BINS];               /* the tile's pairs per digit */
  CO_SHARED uint32_t digit_start[TABLE_WORDS(SORT_BINS)]; /* scans: all keys', then the tile's */
  CO_SHARED uint32_t dest_base[SORT_BINS];             /* where the tile's first pair of a digit goes */
  CO_SHARED uint32_t tmp[SORT_WG];
#if SORT_LOCAL_EXCHANGE
  CO_SHARED sort_key_t tile_keys[TILE];
  CO_SHARED uint32_t tile_values[TILE];
  CO_SHARED uint32_t table[TABLE_WORDS(16 * SORT_WG)]; /* the 4-bit ranking's counters */
#endif
  const uint32_t item = co_local_id();
#if !defined(__OPENCL_VERSION__) && !defined(__CUDACC__)
  tile_index = 0u; /* the host build (one item per group) cannot see that item 0 always sets it */
#endif
  if (item == 0) tile_index = co_atomic_inc(ticket);
  co_barrier();
  const uint32_t tile = tile_index;
  if (tile >= (count + TILE - 1) / TILE) return; /* the whole group: tile_index is shared */
  const uint32_t base = tile * TILE;
  const uint32_t n = co_umin((uint32_t)TILE, count - base);

  /* Count the tile's digits (staging it in local memory on GPUs). */
  for (uint32_t d = item; d < SORT_BINS; d += SORT_WG) counts[d] = 0u;
  co_barrier();
#if SORT_LOCAL_EXCHANGE
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    const uint32_t j = item + i * SORT_WG; /* coalesced */
    if (j < n) {
      const sort_key_t key = keys_in[base + j];
      tile_keys[j] = key;
      tile_values[j] = values_in[base + j];
      co_atomic_inc(&counts[key_digit(key, shift, digit_mask)]);
    }
  }
#else
  for (uint32_t j = 0; j < n; ++j) counts[key_digit(keys_in[base + j], shift, digit_mask)] += 1u;
#endif
  co_barrier();

  /* Publish the counts early, so that later tiles waiting on this one can move on. Tile 0's counts
   * are already its inclusive prefix. */
  CO_GLOBAL uint32_t* mine = lookback + tile * SORT_BINS;
  const uint32_t flag = tile == 0 ? LOOKBACK_PREFIX : LOOKBACK_AGGREGATE;
  for (uint32_t d = item; d < SORT_BINS; d += SORT_WG) co_atomic_xchg(&mine[d], flag | counts[d]);

  /* Where each digit starts among all keys: an exclusive scan of the pass's histogram. */
  for (uint32_t d = item; d < SORT_BINS; d += SORT_WG) digit_start[PAD(d)] = hist[d];
  co_barrier();
  scan_table(digit_start, tmp, SORT_WG, SORT_BINS / SORT_WG);

  /* Decoupled look-back, one digit per item: the pairs of earlier tiles with this digit. */
  for (uint32_t d = item; d < SORT_BINS; d += SORT_WG) {
    uint32_t before = 0u;
    if (tile > 0) {
      uint32_t previous = tile - 1u;
      for (;;) {
        const uint32_t word = co_atomic_load(&lookback[previous * SORT_BINS + d]);
        if ((word & (LOOKBACK_AGGREGATE | LOOKBACK_PREFIX)) == 0u) continue; /* not published yet */
        before += word & LOOKBACK_COUNT;
        if (word & LOOKBACK_PREFIX) break;
        previous -= 1u; /* tile 0 always publishes a prefix, so this stops at 0 */
      }
      co_atomic_xchg(&mine[d], LOOKBACK_PREFIX | (before + counts[d]));
    }
    dest_base[d] = digit_start[PAD(d)] + before;
  }
  co_barrier();

#if SORT_LOCAL_EXCHANGE
  /* Sort the tile by the digit, stably, in local memory: low 4 bits, then high 4 bits. */
  rank_tile_by_nibble(tile_keys, tile_values, table, tmp, n, shift, digit_mask, 0u);
  if (digit_mask > 15u) rank_tile_by_nibble(tile_keys, tile_values, table, tmp, n, shift, digit_mask, 4u);
  /* The tile's first rank of each digit; a pair of digit d and tile rank r goes to
   * dest_base[d] + r - (tile's first rank of d). */
  for (uint32_t d = item; d < SORT_BINS; d += SORT_WG) digit_start[PAD(d)] = counts[d];
  co_barrier();
  scan_table(digit_start, tmp, SORT_WG, SORT_BINS / SORT_WG);
  /* Consecutive items write consecutive ranks; pairs of one digit go to consecutive addresses. */
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    const uint32_t j = item + i * SORT_WG;
    if (j < n) {
      const sort_key_t key = tile_keys[j];
      const uint32_t d = key_digit(key, shift, digit_mask);
      const uint32_t dest = dest_base[d] + j - digit_start[PAD(d)];
      keys_out[dest] = key;
      values_out[dest] = tile_values[j];
    }
  }
#else
  /* One item walks its tile in order: dest_base is the next free place of each digit. */
  for (uint32_t j = 0; j < n; ++j) {
    const sort_key_t key = keys_in[base + j];
    const uint32_t d = key_digit(key, shift, digit_mask);
    const uint32_t dest = dest_base[d];
    dest_base[d] = dest + 1u;
    keys_out[dest] = key;
    values_out[dest] = values_in[base + j];
  }
#endif
}

#endif
