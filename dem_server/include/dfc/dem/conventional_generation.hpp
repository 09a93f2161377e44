#pragma once
// Conventional generation of a bonded DEM body at N g: the route that PCRM
// (pcrm_generation.hpp) is measured against (docs/dem_generation.md,
// "PCRM against conventional generation"; bench/generation_compare.sh).
// The usual procedure of a centrifuge DEM model without replication
// (Potyondy & Cundall 2004 §3.1 for the order; Ciantia et al. 2018,
// doi 10.1680/jencm.18.00025, for the comparison):
//   1. radius expansion of the whole region, closed by its walls and a lid,
//      to the target porosity, without gravity (radius_expansion.hpp: the
//      same drawing, placement and growth as the REV's, over the whole domain);
//   2. relaxation in the closed container until the lid carries at most a
//      given pressure (the growth leaves the packing jammed at megapascals;
//      the lid off at once throws the top spheres out: measured, see the doc);
//   3. the lid removed and N g on: settling until the unbalanced-force ratio is
//      at most the target (settling.hpp). The packing moves to its new
//      simulation with its pair history; the wall contacts start afresh;
//   4. bonds within the bond gap installed with zero load
//      (Simulation::install_bonds_now), then settling again to the same
//      ratio: the bonds take up the self-weight.
// The stress state is what settling leaves: sigma_v follows the weight less
// what the side walls carry by friction, sigma_h / sigma_v is the packing's,
// not a chosen K0 (the PCRM body is given both).
#include <cstdint>
#include <memory>
#include <vector>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/radius_expansion.hpp"
#include "dfc/dem/settling.hpp"
#include "dfc/dem/simulation.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

struct ConventionalSpec {
  RadiusExpansionSpec particles;     ///< radii already upscaled; porosity: the target over the whole region
  BedRegion region;                  ///< the walls' inside: a box or a vertical cylinder
  double density = 0.0;              ///< kg/m3, solid
  double fraction_of_critical = 0.2; ///< of the grown packing's critical step, for settling
  SettlingTarget settling;           ///< stop of the settling before bonding (its check interval also paces the relaxation)
  SettlingTarget bonded_settling;    ///< stop of the settling after bonding
  double relaxed_lid_pressure = 0.0; ///< Pa, the relaxation's stop (e.g. 1 % of the self-weight stress at the floor)
  std::int64_t relaxation_max_steps = 2000000;
};

/// One stage: steps, wall time (not deterministic: reported, never compared) and its stop.
struct GenerationStage {
  std::int64_t steps = 0;
  double seconds = 0.0;
  bool reached = true;  ///< the stage's target was met (the ratio; the relaxation: its lid pressure; expansion: always)
  double ratio = 0.0;   ///< unbalanced-force ratio at the end (the relaxation's: not measured, 0)
};

struct ConventionalBody {
  std::unique_ptr<Simulation> simulation;  ///< the settled, bonded body in the walls (no lid), under N g
  double dt = 0.0;                         ///< s, the settling step
  ExpansionReport expansion_report;
  double lid_pressure = 0.0;               ///< Pa, the lid's normal force over the region's top area at the end of the expansion
  double relaxed_lid_pressure = 0.0;       ///< Pa, the same at the end of the relaxation
  GenerationStage expansion, relaxation, settling, bonded_settling;
};

/// `settings`: the particle law, gravity (N g), damping, threads (bond
/// installation is the procedure's: at stage 3). `walls`: the container
/// without its lid (e.g. floor and side wall), at rest; the lid is a plane at
/// the region's top with the law of walls.front(). UserError if the spheres
/// cannot be placed (radius_expansion.hpp) or `walls` is empty.
[[nodiscard]] ConventionalBody generate_conventionally(const ConventionalSpec& spec, const SimulationSettings& settings, const std::vector<Wall>& walls);

}  // namespace dfc::dem
