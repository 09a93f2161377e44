#pragma once
// Stepping a solver to static equilibrium (docs/theory/fdm.md §1.11: the model is
// in equilibrium when the average unbalanced-force ratio is below a target,
// 1e-5 by default in FLAC3D).
#include "dfc/fdm/solver.hpp"

namespace dfc::fdm {

struct EquilibriumSettings {
  double dt = 1.0;            ///< s; 1 with mass scaling (FLAC's static default)
  double target_ratio = 1e-5; ///< average unbalanced-force ratio
  int min_steps = 10;         ///< so that a new load has been felt before the ratio is trusted
  int max_steps = 200000;
};

/// Steps until the ratio is below the target (after min_steps). Returns the
/// number of steps taken, or -1 if max_steps did not suffice.
[[nodiscard]] int step_to_equilibrium(Solver& solver, const EquilibriumSettings& settings);

}  // namespace dfc::fdm
