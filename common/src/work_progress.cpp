#include "dfc/common/work_progress.hpp"

#include <atomic>

namespace dfc::work_progress {

namespace {
// Defined here, not inline in the header, so that every library linked into a
// server bumps the one counter its heartbeat reads.
std::atomic<std::int64_t> counter{0};
}  // namespace

void advance() noexcept { counter.fetch_add(1, std::memory_order_relaxed); }

std::int64_t current() noexcept { return counter.load(std::memory_order_relaxed); }

}  // namespace dfc::work_progress
