// A std::vector whose resize leaves new elements of a trivial type uninitialised, for the large
// arrays a parallel pass writes in full right after sizing them (the KD-tree's triangles, nodes
// and leaf lists): value-initialising them clears hundreds of MB on one thread first, page faults
// and all, where the parallel pass would fault them in on every core.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace cohort {

// std::allocator with construct() default-initialising (`new (p) U`) instead of
// value-initialising (`new (p) U()`): a no-op for trivial types. Other constructions forward.
template <class T>
class DefaultInitAllocator : public std::allocator<T> {
 public:
  using value_type = T;
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    std::allocator_traits<std::allocator<T>>::construct(static_cast<std::allocator<T>&>(*this), p,
                                                        std::forward<Args>(args)...);
  }
};

template <class T>
using UninitialisedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace cohort
