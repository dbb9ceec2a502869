/* Stable LSD radix sort of (uint64_t key, uint32_t value) pairs, 4 bits per pass, in plain OpenCL C 1.2.
 *
 * One pass over the digit at bits [shift, shift + 4) is three steps, the reduce-then-scan shape of
 * Merrill & Grimshaw, "High Performance and Scalable Radix Sorting" (2011), and of Satish, Harris &
 * Garland, "Designing Efficient Sorting Algorithms for Manycore GPUs" (2009):
 *   sort_histogram   each block (a contiguous tile of TILE pairs, one work-group) counts its digits
 *                    into hist[digit * num_blocks + block];
 *   sort_scan_*      an exclusive scan of that digit-major table gives, for each (digit, block), the
 *                    output position of the block's first pair with that digit (multi-level when the
 *                    table is longer than one work-group's scan tile);
 *   sort_scatter     each block ranks its pairs by digit, stably, and moves them there.
 *
 * Stability: blocks are scanned in input order within each digit; inside a block, work item `item`
 * owns the contiguous run [item * SORT_ITEMS, +SORT_ITEMS) of the tile (the "blocked" arrangement)
 * and keeps one counter per digit in column `item` of a digit-major local table. Scanning that
 * table in (digit, item) order gives each run's first rank per digit, and the item then hands out
 * ranks in input order, so equal digits keep their input order. A counter is only ever touched by
 * the item that owns it: no atomics, no sub-groups, nothing beyond OpenCL C 1.2. Every barrier is
 * reached by the whole work-group (loops around barriers have uniform trip counts; bounds checks sit
 * inside loop bodies).
 *
 * Compile-time sizes, chosen by the host from the device (runtime/sort/radix_sort.cpp):
 *   SORT_WG              work items per work-group of the histogram and scatter kernels;
 *   SORT_ITEMS           pairs per work item, so a tile has SORT_WG * SORT_ITEMS pairs;
 *   SCAN_WG              work items per work-group of the scan kernels (SCAN_ITEMS entries each);
 *   SORT_LOCAL_EXCHANGE  1: stage each tile in local memory and write it out digit by digit, so
 *                        consecutive work items write consecutive addresses (GPUs, whose global
 *                        writes coalesce per warp). 0: each work item reads its run from global
 *                        memory and writes every pair straight to its destination: on a CPU a work
 *                        item is a sequential loop, and the detour through "local" (ordinary cached)
 *                        memory only adds copies. */
#ifndef COHORT_RADIX_SORT_KERNELS_H
#define COHORT_RADIX_SORT_KERNELS_H

#include "common/port.h"

#if !defined(SORT_WG) || !defined(SORT_ITEMS) || !defined(SCAN_WG) || !defined(SORT_LOCAL_EXCHANGE)
#error "SORT_WG, SORT_ITEMS, SCAN_WG and SORT_LOCAL_EXCHANGE must be defined by the host"
#endif

#define RADIX_BITS 4
#define RADIX (1 << RADIX_BITS)          /* digits per pass */
#define TILE (SORT_WG * SORT_ITEMS)      /* pairs per block */
#define SCAN_ITEMS 32                    /* table entries per work item of sort_scan_segments */
#define SCAN_TILE (SCAN_ITEMS * SCAN_WG) /* table entries per work-group of sort_scan_segments */

/* Local tables are scanned with each work item reading 16 or 32 consecutive entries; one padding
 * word every 32 keeps those strided reads free of bank conflicts on 32-bank GPUs (Harris, Sengupta
 * & Owens, GPU Gems 3, ch. 39). */
#define PAD(i) ((i) + ((i) >> 5))
#define TABLE_WORDS(entries) PAD(entries)

#define WG_BARRIER() co_barrier()

/* digit_mask is narrower than 4 bits on the last pass when key_bits is not a multiple of 4: bits
 * above key_bits are then ignored, not sorted. */
CO_INLINE uint32_t key_digit(uint64_t key, uint32_t shift, uint32_t digit_mask) {
  return (uint32_t)(key >> shift) & digit_mask;
}

/* Exclusive scan of one value per work item (Hillis & Steele, "Data Parallel Algorithms", 1986):
 * log2(group) steps over a local array, each a read and a write separated by barriers.
 * Work-inefficient, but over a few hundred values the step count, not the work, is what costs.
 * `group` is a compile-time constant at every call. Returns the exclusive prefix; *total gets the
 * sum over the work-group. */
CO_INLINE uint32_t group_exclusive_scan(uint32_t x, CO_LOCAL uint32_t* tmp, uint32_t* total, const uint32_t group) {
  const uint32_t item = co_local_id();
  tmp[item] = x;
  WG_BARRIER();
  for (uint32_t offset = 1; offset < group; offset <<= 1) {
    const uint32_t y = item >= offset ? tmp[item - offset] : 0u;
    WG_BARRIER();
    tmp[item] += y;
    WG_BARRIER();
  }
  const uint32_t inclusive = tmp[item];
  *total = tmp[group - 1];
  WG_BARRIER(); /* tmp may be reused by the caller */
  return inclusive - x;
}

/* In-place exclusive scan of the per_item * group counters of `table` (linear index i stored at
 * PAD(i)), Blelloch's three phases ("Prefix Sums and Their Applications", 1990): each work item
 * reduces its per_item consecutive entries serially, the per-item sums are scanned across the
 * work-group, and each item rewrites its entries from its offset. The caller must have passed a
 * barrier after filling the table; the scanned table is visible to every work item on return.
 * `group` and `per_item` are compile-time constants at every call. Returns the total. */
CO_INLINE uint32_t scan_table(CO_LOCAL uint32_t* table, CO_LOCAL uint32_t* tmp, const uint32_t group,
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
  WG_BARRIER();
  return total;
}

/* Per block: hist[d * num_blocks + block] = number of the block's pairs whose digit is d. */
CO_KERNEL_WG(SORT_WG)
sort_histogram(CO_GLOBAL const uint64_t* keys, uint32_t count, uint32_t shift, uint32_t digit_mask, uint32_t num_blocks,
               CO_GLOBAL uint32_t* hist) {
  CO_SHARED uint32_t table[TABLE_WORDS(RADIX * SORT_WG)];
  CO_SHARED uint32_t tmp[SORT_WG];
  const uint32_t item = co_local_id();
  const uint32_t block = co_group_id();
  const uint32_t base = block * TILE;
  const uint32_t n = co_umin((uint32_t)TILE, count - base);

  /* Each item counts into its own column. Strided reads (item, item + SORT_WG, ...) coalesce on a
   * GPU and are sequential for one work item on a CPU; counting needs no particular order. */
  for (uint32_t d = 0; d < RADIX; ++d) table[PAD(d * SORT_WG + item)] = 0;
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    const uint32_t j = item + i * SORT_WG;
    if (j < n) table[PAD(key_digit(keys[base + j], shift, digit_mask) * SORT_WG + item)] += 1;
  }
  WG_BARRIER();
  /* Scanning the digit-major table gives each digit's start in the block; the difference of two
   * starts is the digit's count. It reuses the scatter's scan instead of a separate reduction. */
  const uint32_t total = scan_table(table, tmp, SORT_WG, RADIX);
  for (uint32_t d = item; d < RADIX; d += SORT_WG) {
    const uint32_t start = table[PAD(d * SORT_WG)];
    const uint32_t end = d + 1 < RADIX ? table[PAD((d + 1) * SORT_WG)] : total;
    hist[d * num_blocks + block] = end - start;
  }
}

/* Exclusive scan of data[0, n) in segments of SCAN_TILE entries, one per work-group; each segment's
 * total goes to sums[group]. The host scans `sums` the same way (recursively) and adds it back with
 * sort_scan_add when there is more than one segment. */
CO_KERNEL_WG(SCAN_WG) sort_scan_segments(CO_GLOBAL uint32_t* data, uint32_t n, CO_GLOBAL uint32_t* sums) {
  CO_SHARED uint32_t table[TABLE_WORDS(SCAN_TILE)];
  CO_SHARED uint32_t tmp[SCAN_WG];
  const uint32_t item = co_local_id();
  const uint32_t base = co_group_id() * SCAN_TILE;
  for (uint32_t i = 0; i < SCAN_ITEMS; ++i) {
    const uint32_t j = item + i * SCAN_WG; /* coalesced */
    table[PAD(j)] = base + j < n ? data[base + j] : 0u;
  }
  WG_BARRIER();
  const uint32_t total = scan_table(table, tmp, SCAN_WG, SCAN_ITEMS);
  for (uint32_t i = 0; i < SCAN_ITEMS; ++i) {
    const uint32_t j = item + i * SCAN_WG;
    if (base + j < n) data[base + j] = table[PAD(j)];
  }
  if (item == 0) sums[co_group_id()] = total;
}

/* data[i] += scanned_sums[segment of i]: the second half of the multi-level scan. */
CO_KERNEL_WG(SCAN_WG) sort_scan_add(CO_GLOBAL uint32_t* data, uint32_t n, CO_GLOBAL const uint32_t* scanned_sums) {
  const uint32_t i = co_global_id();
  if (i < n) data[i] += scanned_sums[i / SCAN_TILE];
}

/* Moves the block's pairs to their place for this digit: offsets[d * num_blocks + block] (the
 * scanned histogram) is where the block's first pair with digit d goes. */
CO_KERNEL_WG(SORT_WG)
sort_scatter(CO_GLOBAL const uint64_t* keys_in, CO_GLOBAL const uint32_t* values_in, CO_GLOBAL uint64_t* keys_out,
             CO_GLOBAL uint32_t* values_out, uint32_t count, uint32_t shift, uint32_t digit_mask, uint32_t num_blocks,
             CO_GLOBAL const uint32_t* offsets) {
  CO_SHARED uint32_t table[TABLE_WORDS(RADIX * SORT_WG)];
  CO_SHARED uint32_t tmp[SORT_WG];
  CO_SHARED uint32_t out_base[RADIX];
  const uint32_t item = co_local_id();
  const uint32_t block = co_group_id();
  const uint32_t base = block * TILE;
  const uint32_t n = co_umin((uint32_t)TILE, count - base);
  const uint32_t run = item * SORT_ITEMS; /* this item's run of the tile */

#if SORT_LOCAL_EXCHANGE
  CO_SHARED uint64_t tile_keys[TILE];
  CO_SHARED uint32_t tile_values[TILE];
  /* Coalesced load of the tile; then each item takes its run into registers, since the tile is
   * overwritten in rank order below. */
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    const uint32_t j = item + i * SORT_WG;
    if (j < n) {
      tile_keys[j] = keys_in[base + j];
      tile_values[j] = values_in[base + j];
    }
  }
  WG_BARRIER();
  uint64_t keys[SORT_ITEMS];
  uint32_t values[SORT_ITEMS];
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    keys[i] = run + i < n ? tile_keys[run + i] : 0UL;
    values[i] = run + i < n ? tile_values[run + i] : 0u;
  }
#define RUN_KEY(i) keys[i]
#define RUN_VALUE(i) values[i]
#else
#define RUN_KEY(i) keys_in[base + run + (i)]
#define RUN_VALUE(i) values_in[base + run + (i)]
#endif

  /* Count the run's digits into column `item` of the digit-major table. */
  for (uint32_t d = 0; d < RADIX; ++d) table[PAD(d * SORT_WG + item)] = 0;
#if SORT_WG > 1
  for (uint32_t i = 0; i < SORT_ITEMS; ++i)
    if (run + i < n) table[PAD(key_digit(RUN_KEY(i), shift, digit_mask) * SORT_WG + item)] += 1;
  WG_BARRIER(); /* also: with local exchange, every item has read its run before the tile is reused */
  /* After the scan, entry (d, item) is the rank in the block of the run's first pair with digit d,
   * and entry (d, 0) the block's first rank of digit d. A pair of digit d and block rank r goes to
   * offsets[d, block] + r - rank(d, 0). */
  scan_table(table, tmp, SORT_WG, RADIX);
#else
  /* One item per block (the CPU tiling): its run is the whole block, so every digit's ranks start
   * at 0 and the histogram pass has counted already; no second count, no scan. */
  (void)tmp;
#endif
  for (uint32_t d = item; d < RADIX; d += SORT_WG)
    out_base[d] = offsets[d * num_blocks + block] - table[PAD(d * SORT_WG)];
  WG_BARRIER(); /* entry (d, 0) is read above before item 0 advances it below */

  /* Hand out ranks in input order: column `item` of the table now serves as the run's next rank per
   * digit. */
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    if (run + i < n) {
      const uint64_t key = RUN_KEY(i);
      const uint32_t slot = PAD(key_digit(key, shift, digit_mask) * SORT_WG + item);
      const uint32_t rank = table[slot];
      table[slot] = rank + 1;
#if SORT_LOCAL_EXCHANGE
      tile_keys[rank] = key;
      tile_values[rank] = RUN_VALUE(i);
#else
      const uint32_t dest = out_base[key_digit(key, shift, digit_mask)] + rank;
      keys_out[dest] = key;
      values_out[dest] = RUN_VALUE(i);
#endif
    }
  }
#undef RUN_KEY
#undef RUN_VALUE

#if SORT_LOCAL_EXCHANGE
  WG_BARRIER();
  /* The tile is now in rank order: write it out with consecutive items on consecutive ranks. Pairs
   * of one digit occupy consecutive ranks and go to consecutive addresses, so the writes coalesce
   * into runs of about TILE / 16 pairs. */
  for (uint32_t i = 0; i < SORT_ITEMS; ++i) {
    const uint32_t j = item + i * SORT_WG;
    if (j < n) {
      const uint64_t key = tile_keys[j];
      const uint32_t dest = out_base[key_digit(key, shift, digit_mask)] + j;
      keys_out[dest] = key;
      values_out[dest] = tile_values[j];
    }
  }
#endif
}

#endif
