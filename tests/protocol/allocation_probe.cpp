#include "allocation_probe.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<bool> armed{false};
std::atomic<std::size_t> largest_allocation{0};

void* allocate(std::size_t size) {
  if (armed.load(std::memory_order_relaxed)) {
    std::size_t seen = largest_allocation.load(std::memory_order_relaxed);
    while (size > seen && !largest_allocation.compare_exchange_weak(seen, size, std::memory_order_relaxed)) {
    }
  }
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
  throw std::bad_alloc();
}
}  // namespace

// Replacements of the global allocation functions for this test binary only.
void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete[](void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t) noexcept { std::free(memory); }

namespace dfc::protocol::testing {

AllocationProbe::AllocationProbe() {
  largest_allocation.store(0);
  armed.store(true);
}

AllocationProbe::~AllocationProbe() { armed.store(false); }

std::size_t AllocationProbe::largest() const noexcept { return largest_allocation.load(); }

}  // namespace dfc::protocol::testing
