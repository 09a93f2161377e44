#pragma once
// Generation of a DEM body at N g by periodic cell replication (particle
// generator "pcrm", docs/dem_generation.md): an REV prepared at a reference
// K0 stress (rev_preparation.hpp), tiled over the region (pcrm_replication.hpp)
// and scaled to the self-weight stress field (stress_scaling.hpp). The body is
// then equilibrated by the run itself (run.stop_when in the scenario).
#include <optional>
#include <string>

#include "dfc/common/config_reader.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/pcrm_zones.hpp"
#include "dfc/dem/wall.hpp"
#include "dfc/dem/rev_preparation.hpp"
#include "dfc/dem/stress_profile.hpp"
#include "dfc/dem/stress_scaling.hpp"

namespace dfc::dem {

struct PcrmConfig {
  RevSpec rev;                              ///< density, radii and cell already upscaled
  std::optional<double> reference_stress;   ///< Pa, sigma_v of the REV; default: sigma_v at the region's mid-depth
  BedRegion region;
  StressProfile profile;                    ///< unit_weight set at generation from the REV's porosity and |g|
  double protrusion_fraction = 0.0;         ///< pcrm_replication.hpp
  bool seat = true;                         ///< boundary_seating.hpp: seat the body on its walls (rigid and coupling)
  double scale_factor = 1.0;                ///< S of the REV (the section's, or the first zone's)
  std::vector<PcrmZone> zones;              ///< graded upscaling (pcrm_zones.hpp); empty: one zone, the whole region
  double seam_overlap_fraction = 0.1;       ///< pcrm_zones.hpp
};

/// Reads the keys of generator "pcrm" inside "particles" ("rev", "region",
/// "stress", "protrusion_fraction", "zones", ...; not density or generator).
/// Radii and the REV cell are multiplied by `scale_factor`, or with zones by
/// the first zone's S (then `scale_factor` must be 1: the zones give S); the
/// REV's timestep fraction is the model builder's to set.
[[nodiscard]] PcrmConfig read_pcrm(ConfigReader& particles, double scale_factor, double density);


struct GeneratedBody {
  ReplicatedBody body;
  PreparedRev rev;            ///< without its history rows (copied into body)
  StressProfile profile;      ///< with the unit weight used
  double reference_stress = 0.0;  ///< Pa, the REV's measured sigma_v
  StressScalingReport scaling;
  std::size_t seated = 0;     ///< spheres moved onto a wall (boundary_seating.hpp), the coupling wall's included
  std::vector<std::size_t> zone_spheres;  ///< per zone (one zone without zones), before the walls' trimming
  std::size_t seam_removed = 0;           ///< spheres removed where two zones meet (pcrm_zones.hpp)
  std::size_t seam_seated = 0;            ///< spheres seated on an earlier zone's packing (pcrm_zones.hpp)
  double rev_seconds = 0.0, replication_seconds = 0.0;  ///< wall time of the stages (logged, not in results: not deterministic)
};

/// Prepares the REV with `settings`' law, replicates it and scales it to the
/// profile for gravity `gravity` (m/s2, along -z, already N g). ConfigError
/// naming "particles.<key>" for what the inputs cannot give (a law whose
/// bonded state cannot be scaled, no gravity and no surcharge).
[[nodiscard]] GeneratedBody generate_pcrm(const PcrmConfig& config, const SimulationSettings& settings, const Vec3& gravity);

/// Fits the generated body in `simulation` to one of its walls before the
/// first step: removes the spheres the wall cuts by more than the protrusion
/// fraction (at least wall_contact_overlap_fraction) with their pairs, then
/// seats the outermost ones on it (boundary_seating.hpp) unless seating is off.
/// Used for the rigid walls when the model is built and for the coupling wall
/// when it arrives. Adds to body.seated; returns the spheres removed.
std::size_t fit_to_wall(Simulation& simulation, const Wall& wall, const PcrmConfig& config, GeneratedBody& body);

}  // namespace dfc::dem
