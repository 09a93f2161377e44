#include "dfc/dem/sample_preparation.hpp"

#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/measurements.hpp"

namespace dfc::dem {

PreparationReport prepare_sample(Simulation& sim, const PeriodicConfig& config, std::span<const double> final_radius,
                                 const RadiusExpansionSpec& expansion, double fraction_of_critical, double dt, double max_strain_rate) {
  PreparationReport report;
  // 1. Radius expansion (unbonded).
  if (!final_radius.empty()) report.expansion = expand_radii(sim, final_radius, expansion, fraction_of_critical);

  // 2. Servo consolidation: until the stress is within tolerance AND the
  // packing is in equilibrium, checked every check_every steps.
  if (config.consolidation) {
    const ConsolidationSpec& c = *config.consolidation;
    const CellServo servo = make_servo(c.loading, config.servo_gain, max_strain_rate);
    CellStress stress;
    while (report.consolidation_steps < c.max_steps) {
      stress = servo_step(sim, servo, dt);
      ++report.consolidation_steps;
      if (report.consolidation_steps % c.check_every != 0) continue;
      report.stress_error = servo.relative_error(stress);
      if (report.stress_error <= c.tolerance && measure(sim).unbalanced_force_ratio <= c.unbalanced_force_ratio) {
        report.consolidated = true;
        break;
      }
    }
    sim.set_cell_strain_rate({});
    if (!report.consolidated) {
      std::ostringstream msg;
      msg << "periodic.consolidation did not reach its target in " << c.max_steps << " steps (relative stress error " << report.stress_error
          << ", unbalanced force ratio " << measure(sim).unbalanced_force_ratio
          << "); raise periodic.consolidation.max_steps or periodic.servo.max_strain_rate_per_s, or loosen the tolerance";
      throw SolverError(msg.str());
    }
    report.stress = stress.diagonal();
  }

  // 3. Bonds within the bond gap, on the prepared packing (one step installs them).
  if (sim.settings().particle_law.bonded()) {
    sim.install_bonds_now();
    sim.step(dt);
    report.bonds_installed = sim.bond_counts().intact;
  }
  report.porosity = cell_porosity(sim.particles(), *sim.periodic_cell());
  return report;
}

}  // namespace dfc::dem
