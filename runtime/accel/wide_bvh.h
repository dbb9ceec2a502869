// The BVH a render traces (--tree bvh4, bvh8 or bvh8f), or none (a KD-tree): what the upload, the memory
// accounting and the trace benchmark take. Converts from either BVH's pointer, so a caller passes
// what it has.
#pragma once

#include <cstddef>

#include "runtime/accel/bvh4.h"
#include "runtime/accel/bvh8.h"
#include "runtime/accel/bvh8f.h"

namespace cohort {

struct WideBvh {
  const Bvh4* bvh4 = nullptr;
  const Bvh8* bvh8 = nullptr;
  const Bvh8f* bvh8f = nullptr;

  WideBvh() = default;
  WideBvh(std::nullptr_t) {}
  WideBvh(const Bvh4* b) : bvh4(b) {}
  WideBvh(const Bvh8* b) : bvh8(b) {}
  WideBvh(const Bvh8f* b) : bvh8f(b) {}
  explicit operator bool() const { return bvh4 || bvh8 || bvh8f; }
};

}  // namespace cohort
