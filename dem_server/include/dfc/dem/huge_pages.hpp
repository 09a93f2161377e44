#pragma once
// Large arrays on transparent huge pages, where the kernel gives them on
// request (Linux's "madvise" mode, Debian's default). A rebuild of the
// neighbour lists allocates the pair history afresh (the paper's open pile:
// 2.6 million rows of 184 B); faulting that in 4 KiB pages cost about as much
// as copying it (a profile of the rebuild: page faults 29 %, most in the
// kernel's zeroing and accounting), 2 MiB pages 512 times fewer. The contents
// and the arithmetic are unchanged: only how the memory is mapped.
#include <cstddef>
#include <vector>

namespace dfc::dem {

/// Asks the kernel to back the whole 2 MiB pages within [data, data + bytes)
/// by huge pages when they are first touched. Does nothing where there is no
/// such request (other systems) or when the kernel declines it.
void advise_huge_pages(void* data, std::size_t bytes) noexcept;

/// The size of the units advise_huge_pages and release_whole_units work in.
inline constexpr std::size_t huge_page_bytes = std::size_t(2) << 20;

/// Gives the whole 2 MiB units within [data, data + bytes) back to the kernel:
/// their pages stop counting as resident, and read as zeros if touched
/// again. For an array whose contents are no longer needed while the array
/// still exists (a rebuild's previous history, move_matched_rows). The
/// partial units at the ends are kept: they may hold other data (the
/// allocator's own header before the first element). Does nothing where
/// there is no such request (other systems).
void release_whole_units(void* data, std::size_t bytes) noexcept;

/// v.reserve(n), the new storage advised onto huge pages before anything
/// touches it (a vector with room for n already keeps its pages).
template <class T, class Allocator>
void reserve_with_huge_pages(std::vector<T, Allocator>& v, std::size_t n) {
  if (v.capacity() >= n) return;
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
}

}  // namespace dfc::dem
