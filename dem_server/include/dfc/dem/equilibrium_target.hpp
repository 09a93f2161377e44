#pragma once
// When a servo-controlled preparation stage counts as finished: the stress is
// within a relative tolerance of its target AND the packing is in equilibrium
// (unbalanced force ratio, measurements.hpp), checked every check_every steps.
// Shared by the periodic cell's consolidation and the triaxial walls' confinement.
#include <cstdint>
#include <functional>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/sections/dem_sections.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct EquilibriumTarget {
  double tolerance = sections::kDefaultEquilibriumTolerance;  ///< relative stress error at which the target counts as reached
  double unbalanced_force_ratio = sections::kDefaultEquilibriumUnbalancedForceRatio;  ///< and the packing as in equilibrium
  std::int64_t max_steps = sections::kDefaultEquilibriumMaxSteps;
  std::int64_t check_every = sections::kDefaultEquilibriumCheckEvery;
};

/// Reads "tolerance", "unbalanced_force_ratio", "max_steps", "check_every" (the caller finishes).
[[nodiscard]] EquilibriumTarget read_equilibrium_target(ConfigReader& cfg);

struct EquilibriumRun {
  bool reached = false;
  std::int64_t steps = 0;
  double stress_error = 0.0;  ///< relative, at the last check
};

/// Calls `servo_step` (one step of `simulation`, returning the relative stress
/// error it measured) until the target is met or max_steps were taken.
[[nodiscard]] EquilibriumRun run_to_equilibrium(const Simulation& simulation, const EquilibriumTarget& target,
                                                const std::function<double()>& servo_step);

}  // namespace dfc::dem
