#pragma once
// Sample generation by radius expansion in a periodic cell (docs/dem_periodic.md §5)
// or in a box of fixed walls (docs/dem_triaxial_walls.md).
//
// The method of the Zheng–Ciantia examples (docs/theory/upscaling_and_pcrm.md §3:
// "radius expansion with multiplier 1.6 applied in 10 steps"; PFC's
// radius-expansion generation, Potyondy & Cundall 2004 §3.1):
//   1. draw radii uniform in [radius_min, radius_max] until their volume
//      reaches (1 - n) V, then scale them all by the cube root of the small
//      remainder so that the solid volume is (1 - n) V exactly (n the target
//      porosity, V the cell volume);
//   2. place the spheres at random (PortableRandom: seeded, the same on every
//      platform) without overlap at their radii divided by the multiplier m;
//   3. grow them in `stages` steps, r_s = r m^(s/stages - 1) (geometric: equal
//      volume ratio per stage), with `relax_steps` cycles of local damping after each.
// After the last stage the porosity is the target to round-off; relaxation
// does not change it (the cell is fixed), a later stress servo does.
//
// Radii come from the configuration only, so that particle upscaling by S is
// the caller's multiplication of radius_min and radius_max (and the
// cell) before generation.
#include <cstdint>
#include <span>
#include <vector>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/periodic_cell.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct RadiusExpansionSpec {
  double radius_min = 0.0;       ///< m, final radii (before the exact-porosity scaling)
  double radius_max = 0.0;       ///< m
  double porosity = 0.5;         ///< target porosity of the cell after the last stage
  double multiplier = 1.6;       ///< final / initial radius
  int stages = 10;
  std::int64_t relax_steps = 1000;  ///< cycles after each stage
  std::uint64_t seed = 1;
};

struct ExpansionPacking {
  std::vector<GeneratedSphere> spheres;  ///< at the initial radii (final / multiplier); particle id = index
  std::vector<double> final_radius;      ///< m, by particle id
};

/// Steps 1–2. Open axes of the cell keep whole spheres inside [lo, hi].
/// Throws UserError if a sphere cannot be placed (too dense a start).
[[nodiscard]] ExpansionPacking place_for_radius_expansion(const RadiusExpansionSpec& spec, const PeriodicCell& cell);

/// Steps 1–2 in a region closed by walls (a box, or a vertical cylinder:
/// conventional_generation.hpp): the solid volume is (1 - n) times the
/// region's, every sphere lies whole inside it (placement rejects the others).
[[nodiscard]] ExpansionPacking place_for_radius_expansion(const RadiusExpansionSpec& spec, const BedRegion& region);

/// m, radius after `stage` of `stages` (stage 0: final / multiplier, stage = stages: final).
[[nodiscard]] double stage_radius(double final_radius, double multiplier, int stage, int stages) noexcept;

struct ExpansionReport {
  double porosity_geometric = 0.0;  ///< after the last stage, before its relaxation (= target to round-off)
  double porosity_relaxed = 0.0;    ///< after the last relaxation
  std::int64_t steps = 0;
};

/// Step 3 on a simulation holding the packing (ids = indices into final_radius)
/// in a container of `volume` (m3: the periodic cell, or the box of fixed walls
/// the spheres were placed in). Each relaxation runs at fraction_of_critical of
/// the critical step of the current radii.
ExpansionReport expand_radii(Simulation& simulation, std::span<const double> final_radius, const RadiusExpansionSpec& spec,
                             double fraction_of_critical, double volume);

}  // namespace dfc::dem
