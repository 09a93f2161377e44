#include "dfc/dem/equilibrium_target.hpp"

#include "dfc/dem/measurements.hpp"

namespace dfc::dem {

EquilibriumTarget read_equilibrium_target(ConfigReader& cfg) {
  EquilibriumTarget t;
  // Defaults and bounds: the declaration (dfc/common/sections/dem_sections.cpp, equilibrium_target_keys).
  t.tolerance = cfg.number("tolerance");
  t.unbalanced_force_ratio = cfg.number("unbalanced_force_ratio");
  t.max_steps = cfg.integer("max_steps");
  t.check_every = cfg.integer("check_every");
  return t;
}

EquilibriumRun run_to_equilibrium(const Simulation& sim, const EquilibriumTarget& target, const std::function<double()>& servo_step) {
  EquilibriumRun run;
  while (run.steps < target.max_steps) {
    const double error = servo_step();
    ++run.steps;
    if (run.steps % target.check_every != 0) continue;
    run.stress_error = error;
    if (error <= target.tolerance && measure(sim).unbalanced_force_ratio <= target.unbalanced_force_ratio) {
      run.reached = true;
      break;
    }
  }
  return run;
}

}  // namespace dfc::dem
