#pragma once
// Preparation of a periodic REV before the coupled run (docs/dem_periodic.md §5),
// or of a sample confined in six walls (docs/dem_triaxial_walls.md),
// in PFC's order (Potyondy & Cundall 2004 §3.1; the Zheng–Ciantia examples,
// docs/theory/upscaling_and_pcrm.md §3): radius expansion to the target porosity,
// servo consolidation to the target stress, then bonds within the bond gap.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "dfc/dem/periodic_config.hpp"
#include "dfc/dem/radius_expansion.hpp"
#include "dfc/dem/simulation.hpp"
#include "dfc/dem/triaxial_walls.hpp"

namespace dfc::dem {

struct PreparationReport {
  std::optional<ExpansionReport> expansion;
  bool consolidated = false;           ///< the consolidation target was met (false also without a consolidation)
  std::int64_t consolidation_steps = 0;
  double stress_error = 0.0;           ///< relative, at the end of consolidation
  Vec3 stress;                         ///< Pa, compression positive, at the end: the cell stress diagonal, or in
                                       ///< walls the two lateral pairs' and the platens' stresses
  double porosity = 0.0;               ///< at the end of preparation (of the cell, or of the walls' box)
  std::int64_t bonds_installed = 0;
};

/// Bonds within the bond gap on a prepared packing (one step of dt installs
/// them, with zero load); returns the intact bonds (0 for an unbonded law).
std::int64_t install_bonds(Simulation& simulation, double dt);

struct Consolidation {
  std::int64_t steps = 0;
  double stress_error = 0.0;  ///< relative, at the last check
  Vec3 stress;                ///< Pa, compression positive: the cell stress diagonal at the end
};

/// Servo-controls the periodic cell of `simulation` to `spec`'s loading until
/// its target is met (equilibrium_target.hpp), then stops the cell. SolverError
/// after spec.max_steps, naming the keys `key` (the consolidation block) and
/// `servo_key` (its servo) to change.
Consolidation consolidate(Simulation& simulation, const ConsolidationSpec& spec, double gain, double max_strain_rate, double dt,
                          const std::string& key, const std::string& servo_key);

/// Runs the stages on `simulation` (already holding the particles and the
/// cell): expansion if `final_radius` is not empty, consolidation if the
/// config has one, then installs the bonds of a bonded law. `dt` is the step
/// of the consolidation; SolverError if it does not converge in max_steps.
PreparationReport prepare_sample(Simulation& simulation, const PeriodicConfig& config, std::span<const double> final_radius,
                                 const RadiusExpansionSpec& expansion, double fraction_of_critical, double dt, double max_strain_rate);

/// A radius expansion to run first: the final radii by particle id (empty: none).
struct ExpansionStage {
  std::span<const double> final_radius;
  const RadiusExpansionSpec& spec;
  double fraction_of_critical = 0.2;
};

/// A sample in six walls (triaxial_walls.hpp): radius expansion in the fixed
/// walls if `expansion` has final radii, every wall servo-controlled to the
/// confining stress until `target` is met (SolverError after max_steps, naming
/// the triaxial.confinement keys), the walls stopped, then the bonds of a
/// bonded law installed. `control.platen_speed` must be empty.
PreparationReport confine_in_walls(Simulation& simulation, const TriaxialWalls& box, const TriaxialControl& control,
                                   const EquilibriumTarget& target, const ExpansionStage& expansion, double dt);

}  // namespace dfc::dem
