#pragma once
// Declarations of the dem_server section of a scenario (declaration.hpp):
// the particles and their generators, the contact laws (dem_contact_laws.hpp),
// damping and time step, walls, the pile, the UCS and triaxial loadings and
// the periodic cell. dem_server's parser (dem_server/src/config/) reads them,
// `dem_server --help` prints them and scenario.schema.json publishes them.
#include "dfc/common/declaration.hpp"

namespace dfc::sections {

/// The whole configuration object of dem_server (participants.<name>.config).
[[nodiscard]] const SectionDeclaration& dem_server();

/// Local non-viscous damping alpha of the DEM unless "damping.local" says
/// otherwise (Cundall 1987; the value PFC uses by default for quasi-static runs).
inline constexpr double kDefaultLocalDamping = 0.7;

}  // namespace dfc::sections
