// Critical time step (timestep.hpp): beyond it the settled bed blows up or the
// run is refused; at the default fraction 0.2 it stays at rest.
#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/common/errors.hpp"

namespace dfc::dem {
namespace {

double energy_scale(const Simulation& sim) { return measure(sim).total_weight * 1e-3; }  // lifting every particle by 1 mm

TEST(CriticalTimestep, RunRefusesAStepAboveCritical) {
  Simulation sim = test::settled_box_bed().simulation;
  const std::int64_t steps = sim.step_count();
  EXPECT_THROW(sim.run(1, 1.5 * sim.critical_timestep()), SolverError);
  EXPECT_EQ(sim.step_count(), steps);
}

TEST(CriticalTimestep, OneAndAHalfTimesCriticalBlowsUp) {
  Simulation sim = test::settled_box_bed().simulation;
  const double dt = 1.5 * sim.critical_timestep();
  bool blew_up = false;
  try {
    for (int s = 0; s < 5000 && !blew_up; ++s) {
      sim.step(dt);
      blew_up = s % 100 == 0 && measure(sim).kinetic_energy > energy_scale(sim);
    }
  } catch (const SolverError&) {
    blew_up = true;
  }
  EXPECT_TRUE(blew_up) << "the estimate is too conservative: 1.5 x dt_crit stayed stable";
}

TEST(CriticalTimestep, FractionPointTwoStaysAtRest) {
  Simulation sim = test::settled_box_bed().simulation;
  sim.run(5000, 0.2 * sim.critical_timestep());
  // Settled: kinetic energy orders of magnitude below the 1 mm lift energy.
  EXPECT_LT(measure(sim).kinetic_energy, 1e-4 * energy_scale(sim));
}

}  // namespace
}  // namespace dfc::dem
