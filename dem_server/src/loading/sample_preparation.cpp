#include "dfc/dem/sample_preparation.hpp"

#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/measurements.hpp"

namespace dfc::dem {

std::int64_t install_bonds(Simulation& sim, double dt) {
  if (!sim.settings().particle_law.bonded()) return 0;
  sim.install_bonds_now();
  sim.step(dt);
  return sim.bond_counts().intact;
}

Consolidation consolidate(Simulation& sim, const ConsolidationSpec& spec, double gain, double max_strain_rate, double dt,
                          const std::string& key, const std::string& servo_key) {
  const CellServo servo = make_servo(spec.loading, gain, max_strain_rate);
  CellStress stress;
  const EquilibriumRun run = run_to_equilibrium(sim, spec, [&] {
    stress = servo_step(sim, servo, dt);
    return servo.relative_error(stress);
  });
  sim.set_cell_strain_rate({});
  if (!run.reached) {
    std::ostringstream msg;
    msg << key << " did not reach its target in " << spec.max_steps << " steps (relative stress error " << run.stress_error
        << ", unbalanced force ratio " << measure(sim).unbalanced_force_ratio << "); raise " << key << ".max_steps or " << servo_key
        << ".max_strain_rate_per_s, or loosen the tolerance";
    throw SolverError(msg.str());
  }
  return {run.steps, run.stress_error, stress.diagonal()};
}

PreparationReport prepare_sample(Simulation& sim, const PeriodicConfig& config, std::span<const double> final_radius,
                                 const RadiusExpansionSpec& expansion, double fraction_of_critical, double dt, double max_strain_rate) {
  PreparationReport report;
  // 1. Radius expansion (unbonded).
  if (!final_radius.empty()) report.expansion = expand_radii(sim, final_radius, expansion, fraction_of_critical, sim.periodic_cell()->volume());

  // 2. Servo consolidation: until the stress is within tolerance AND the
  // packing is in equilibrium, checked every check_every steps.
  if (config.consolidation) {
    const Consolidation done = consolidate(sim, *config.consolidation, config.servo_gain, max_strain_rate, dt, "periodic.consolidation",
                                           "periodic.servo");
    report.consolidated = true;
    report.consolidation_steps = done.steps;
    report.stress_error = done.stress_error;
    report.stress = done.stress;
  }

  report.bonds_installed = install_bonds(sim, dt);
  report.porosity = cell_porosity(sim.particles(), *sim.periodic_cell());
  return report;
}

PreparationReport confine_in_walls(Simulation& sim, const TriaxialWalls& box, const TriaxialControl& control, const EquilibriumTarget& target,
                                   const ExpansionStage& expansion, double dt) {
  PreparationReport report;
  const BoxAxes axes = box_axes(box_vertices(sim.walls(), box));
  if (!expansion.final_radius.empty())
    report.expansion = expand_radii(sim, expansion.final_radius, expansion.spec, expansion.fraction_of_critical,
                                    box_size(sim.walls(), box, axes).volume());
  BoxStress stress;
  LocalEngine engine(sim);  // the preparation runs before the body is decomposed: every process prepares it whole
  const EquilibriumRun run = run_to_equilibrium(sim, target, [&] {
    stress = triaxial_step(engine, box, axes, control, dt);
    return confinement_error(stress, control);
  });
  for (const std::size_t w : box.in_order()) sim.set_wall_velocity(w, {});
  report.consolidated = run.reached;
  report.consolidation_steps = run.steps;
  report.stress_error = run.stress_error;
  if (!run.reached) {
    std::ostringstream msg;
    msg << "triaxial.confinement did not reach the confining stress in " << target.max_steps << " steps (relative stress error "
        << run.stress_error << ", unbalanced force ratio " << measure(sim).unbalanced_force_ratio
        << "); raise triaxial.confinement.max_steps or triaxial.servo.max_strain_rate_per_s, or loosen the tolerance";
    throw SolverError(msg.str());
  }
  report.stress = {0.5 * (stress.wall[2] + stress.wall[3]), 0.5 * (stress.wall[4] + stress.wall[5]), stress.axial()};
  report.bonds_installed = install_bonds(sim, dt);
  report.porosity = box_porosity(sim.particles(), box_size(sim.walls(), box, axes));
  return report;
}

}  // namespace dfc::dem
