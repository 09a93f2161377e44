#pragma once
// Preparation of a periodic REV before the coupled run (docs/dem_periodic.md §5),
// in PFC's order (Potyondy & Cundall 2004 §3.1; the Zheng–Ciantia examples,
// reference/dem-physics.md §3.7): radius expansion to the target porosity,
// servo consolidation to the target stress, then bonds within the bond gap.
#include <cstdint>
#include <optional>
#include <span>

#include "dfc/dem/periodic_config.hpp"
#include "dfc/dem/radius_expansion.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct PreparationReport {
  std::optional<ExpansionReport> expansion;
  bool consolidated = false;           ///< the consolidation target was met (false also without a consolidation)
  std::int64_t consolidation_steps = 0;
  double stress_error = 0.0;           ///< relative, at the end of consolidation
  Vec3 stress;                         ///< Pa, cell stress diagonal at the end (compression positive)
  double porosity = 0.0;               ///< at the end of preparation
  std::int64_t bonds_installed = 0;
};

/// Runs the stages on `simulation` (already holding the particles and the
/// cell): expansion if `final_radius` is not empty, consolidation if the
/// config has one, then installs the bonds of a bonded law. `dt` is the step
/// of the consolidation; SolverError if it does not converge in max_steps.
PreparationReport prepare_sample(Simulation& simulation, const PeriodicConfig& config, std::span<const double> final_radius,
                                 const RadiusExpansionSpec& expansion, double fraction_of_critical, double dt, double max_strain_rate);

}  // namespace dfc::dem
