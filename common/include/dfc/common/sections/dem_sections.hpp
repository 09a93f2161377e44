#pragma once
// Declarations of the dem_server section of a scenario (declaration.hpp):
// the particles and their generators, the contact laws (dem_contact_laws.hpp),
// damping and time step, walls, the pile, the UCS and triaxial loadings and
// the periodic cell. dem_server's parser (dem_server/src/config/) reads them,
// `dem_server --help` prints them and scenario.schema.json publishes them.
#include <cstdint>

#include "dfc/common/declaration.hpp"

namespace dfc::sections {

/// The whole configuration object of dem_server (participants.<name>.config).
[[nodiscard]] const SectionDeclaration& dem_server();

/// Local non-viscous damping alpha of the DEM unless "damping.local" says
/// otherwise (Cundall 1987; the value PFC uses by default for quasi-static runs).
inline constexpr double kDefaultLocalDamping = 0.7;

/// Defaults of the declared keys that the DEM's configuration structs also
/// carry as member initialisers (a struct built without the parser, in the
/// tests and the REV builder, gets the same values).
inline constexpr double kDefaultServoGain = 0.5;                     ///< servo.gain
inline constexpr double kDefaultFractionOfCritical = 0.2;            ///< timestep.fraction_of_critical
inline constexpr double kDefaultMaxOverlapFraction = 0.5;            ///< timestep.max_overlap_fraction
inline constexpr double kDefaultEquilibriumTolerance = 0.01;         ///< <stage>.tolerance
inline constexpr double kDefaultEquilibriumUnbalancedForceRatio = 0.01;  ///< <stage>.unbalanced_force_ratio
inline constexpr std::int64_t kDefaultEquilibriumMaxSteps = 200000;     ///< <stage>.max_steps
inline constexpr std::int64_t kDefaultEquilibriumCheckEvery = 100;      ///< <stage>.check_every
/// particles.rev.installation_stress_pa: the isotropic stress at which the
/// REV's unbonded packing is consolidated before its bonds are installed
/// (Potyondy & Cundall 2004 §3.1, step 2), the same at every g-level
/// (docs/dem_generation.md, "Changing the g-level").
inline constexpr double kDefaultRevInstallationStress = 1e5;         ///< Pa

}  // namespace dfc::sections
