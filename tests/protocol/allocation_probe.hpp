#pragma once
// AllocationProbe: records the largest single heap allocation made while one
// is alive. This test binary replaces the global operator new
// (allocation_probe.cpp) so that a test can prove the codec rejects a header
// declaring a huge array without allocating in proportion to it (SPEC.md §8).
#include <cstddef>

namespace dfc::protocol::testing {

class AllocationProbe {
 public:
  AllocationProbe();
  ~AllocationProbe();
  AllocationProbe(const AllocationProbe&) = delete;
  AllocationProbe& operator=(const AllocationProbe&) = delete;

  /// Bytes of the largest single allocation since construction.
  [[nodiscard]] std::size_t largest() const noexcept;
};

}  // namespace dfc::protocol::testing
