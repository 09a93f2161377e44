#include "dfc/dem/huge_pages.hpp"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dfc::dem {

#if defined(__linux__)
namespace {
/// madvise(advice) on the whole 2 MiB units within [data, data + bytes).
void advise_whole_units(void* data, std::size_t bytes, int advice) noexcept {
  constexpr std::uintptr_t unit = huge_page_bytes;
  const auto start = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t begin = (start + unit - 1) & ~(unit - 1);
  const std::uintptr_t end = (start + bytes) & ~(unit - 1);
  // A refusal (THP off, an old kernel) leaves ordinary, resident pages: the
  // time or the memory figure would show it, never the results.
  if (end > begin) static_cast<void>(madvise(reinterpret_cast<void*>(begin), end - begin, advice));
}
}  // namespace
#endif

void advise_huge_pages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  advise_whole_units(data, bytes, MADV_HUGEPAGE);
#endif
}

void release_whole_units([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_DONTNEED)
  advise_whole_units(data, bytes, MADV_DONTNEED);
#endif
}

}  // namespace dfc::dem
