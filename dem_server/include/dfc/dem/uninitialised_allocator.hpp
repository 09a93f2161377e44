#pragma once
// An allocator whose vectors leave new elements of trivial types
// uninitialised (`resize(n)` constructs `T` by default-initialisation, not
// value-initialisation), so that the threads that fill an array are the first
// to touch its pages. Why: a rebuild of the paper's open pile allocates the
// pair history afresh (2.6 million rows of 184 B); `assign(n, 0.0)` made one
// thread take every page fault, and the kernel's clearing of those pages was
// the largest serial part of the run (bench/serial_fraction.py: about half of
// the rebuild's serial time). Filled by the parallel copy instead, the pages
// are cleared on every core. Every element must then be written before it is
// read: the users of such a vector say where.
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace dfc::dem {

template <class T>
class UninitialisedAllocator : public std::allocator<T> {
 public:
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  using std::allocator<T>::allocator;
  UninitialisedAllocator() noexcept = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor): as std::allocator

  /// `new T` instead of `new T()`: no zeroing of trivial types.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    std::construct_at(p, std::forward<Args>(args)...);
  }
};

template <class T, class U>
constexpr bool operator==(const UninitialisedAllocator<T>&, const UninitialisedAllocator<U>&) noexcept {
  return true;
}

/// Rows of doubles that a rebuild fills in parallel (PairContacts::history).
using UninitialisedDoubles = std::vector<double, UninitialisedAllocator<double>>;

}  // namespace dfc::dem
