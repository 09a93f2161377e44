#pragma once
// OpenMP policy of the DEM loops.
#include <cstdint>

namespace dfc::dem {

/// Loops over fewer items than this run on one thread: below it the cost of
/// waking threads (tens of microseconds, far more on a loaded machine)
/// exceeds the work. Results do not depend on it (no loop's result depends
/// on how it is split).
inline constexpr std::int64_t min_parallel_items = 2048;

}  // namespace dfc::dem
