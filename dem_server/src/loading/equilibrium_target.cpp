#include "dfc/dem/equilibrium_target.hpp"

#include "dfc/dem/measurements.hpp"

namespace dfc::dem {

EquilibriumTarget read_equilibrium_target(ConfigReader& cfg) {
  EquilibriumTarget t;
  t.tolerance = cfg.number("tolerance", 0.01, Bounds{0.0, 1.0, true});
  t.unbalanced_force_ratio = cfg.number("unbalanced_force_ratio", 0.01, Bounds{0.0, 1.0, true});
  t.max_steps = cfg.integer("max_steps", 200000, 1);
  t.check_every = cfg.integer("check_every", 100, 1);
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
