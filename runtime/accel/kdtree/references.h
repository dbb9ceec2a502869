// The KD-tree build's triangle references (a kept triangle and its extent clipped to the node's
// cell), the sorted extents the exact SAH sweeps, and the uninitialised buffers and stack that hold
// the references of one build task. Internal to runtime/accel/kdtree.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/scene/bounds.h"

namespace cohort::kd {

// One axis of a node's references for the exact sweep: where each extent of non-zero width starts
// and ends, and where each flat one (a triangle lying in a plane across the axis) lies. Sorted, these
// are Wald & Havran's event lists without the events: their sweep needs only how many extents
// start, end or lie at each position, so three float arrays sort faster than tagged events and give
// the same planes.
struct AxisExtents {
  std::vector<float> starts, ends, flats;

  void clear() {
    starts.clear();
    ends.clear();
    flats.clear();
  }
  // -0 is taken as +0, so equal positions compare equal and the plane is never -0.
  void add(float lo, float hi) {
    if (lo == hi) {
      flats.push_back(lo + 0.f);
    } else {
      starts.push_back(lo + 0.f);
      ends.push_back(hi + 0.f);
    }
  }
  // Sorts the three lists, every position of which lies in the cell's [lo, hi] along the axis.
  void sort(float lo, float hi);
};

using NodeExtents = std::array<AxisExtents, 3>;

// A triangle reference: a kept triangle and its extent clipped to the cell of the node that holds
// it (Havran's perfect splits). A node's references keep ascending triangle order, so leaf lists
// are ascending and the tree does not depend on which thread moved the references.
struct Ref {
  Bounds box;
  std::uint32_t tri;
};

// Uninitialised room for n values, for buffers whose every entry is written before it is read:
// the references the branch-free partitions write (each written to both sides and kept by the
// count of the side it lies on), the binned search's per-reference bins and gathered extents.
// (T is an implicit-lifetime type, so its allocator's storage holds Ts once they are written; a
// vector would first initialise every element, on one thread.) Grows, by at least doubling,
// without keeping its contents.
template <class T>
class UninitialisedArray {
 public:
  UninitialisedArray() = default;
  UninitialisedArray(UninitialisedArray&& other) noexcept { swap(other); }
  UninitialisedArray& operator=(UninitialisedArray&& other) noexcept {
    UninitialisedArray(std::move(other)).swap(*this);
    return *this;
  }
  ~UninitialisedArray() { release(); }

  // Room for at least n values.
  T* room(std::size_t n) {
    if (n > capacity_) {
      const std::size_t capacity = std::max(n, 2 * capacity_);
      release();
      data_ = allocator_.allocate(capacity);
      capacity_ = capacity;
    }
    return data_;
  }
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t capacity() const { return capacity_; }

 private:
  void swap(UninitialisedArray& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(capacity_, other.capacity_);
  }
  void release() {
    if (data_ != nullptr) allocator_.deallocate(data_, capacity_);
    data_ = nullptr;
    capacity_ = 0;
  }
  std::allocator<T> allocator_;
  T* data_ = nullptr;
  std::size_t capacity_ = 0;
};

using RefBuffer = UninitialisedArray<Ref>;

// A task's references as a stack (kdtree_builder.cpp): a node's range, with its children's
// pushed on top. Grown uninitialised (RefBuffer), so the parallel splits fill it from several
// threads, page faults included, where a vector would first initialise it on one thread.
class RefStack {
 public:
  RefStack() = default;
  RefStack(RefStack&& other) noexcept
      : storage_(std::move(other.storage_)), size_(std::exchange(other.size_, 0)) {}
  RefStack& operator=(RefStack&& other) noexcept {
    storage_ = std::move(other.storage_);
    size_ = std::exchange(other.size_, 0);
    return *this;
  }

  std::size_t size() const { return size_; }
  Ref* data() { return storage_.data(); }
  const Ref* data() const { return storage_.data(); }
  const Ref& operator[](std::size_t i) const { return storage_.data()[i]; }
  std::span<const Ref> span(std::size_t first, std::size_t count) const {
    return {storage_.data() + first, count};
  }
  // Makes the stack n references longer and returns the first of them, not yet written.
  Ref* push(std::size_t n) {
    if (size_ + n > storage_.capacity()) {
      RefBuffer grown;
      std::copy_n(storage_.data(), size_, grown.room(std::max(size_ + n, 2 * storage_.capacity())));
      storage_ = std::move(grown);
    }
    size_ += n;
    return storage_.data() + size_ - n;
  }
  void pop_to(std::size_t size) { size_ = std::min(size, size_); }

 private:
  RefBuffer storage_;
  std::size_t size_ = 0;
};

// A triangle's vertex as the clipping and the SAH take it.
inline glm::vec3 vertex(const co_float4& v) { return {v.x, v.y, v.z}; }

}  // namespace cohort::kd
