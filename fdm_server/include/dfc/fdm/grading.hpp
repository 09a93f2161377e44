#pragma once
// Geometric grading of a structured mesh direction.
#include <vector>

#include "dfc/fdm/types.hpp"

namespace dfc::fdm {

/// n + 1 coordinates from `start` to `end` (both exact) whose spacings form a
/// geometric series Δ_{k+1} = ratio · Δ_k, counted from `start`. ratio = 1 is
/// uniform; ratio > 1 makes the zones finer at `start`. Requires n >= 1, ratio > 0.
[[nodiscard]] std::vector<double> geometric_spacing(double start, double end, Index n, double ratio);

}  // namespace dfc::fdm
