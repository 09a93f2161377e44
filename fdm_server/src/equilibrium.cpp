#include "dfc/fdm/equilibrium.hpp"

namespace dfc::fdm {

int step_to_equilibrium(Solver& solver, const EquilibriumSettings& settings) {
  for (int step = 1; step <= settings.max_steps; ++step) {
    solver.step(settings.dt);
    if (step >= settings.min_steps && solver.unbalanced_force_ratio() < settings.target_ratio) return step;
  }
  return -1;
}

}  // namespace dfc::fdm
