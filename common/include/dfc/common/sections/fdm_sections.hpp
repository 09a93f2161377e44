#pragma once
// Declarations of the fdm_server section of a scenario (declaration.hpp):
// every key, its type, unit, default, bounds and one-line doc, read by
// fdm_server's parser (fdm_server/src/fdm_config.cpp), printed by its --help
// and published in scenario.schema.json.
#include "dfc/common/declaration.hpp"

namespace dfc::sections {

/// The whole configuration object of fdm_server (participants.<name>.config).
[[nodiscard]] const SectionDeclaration& fdm_server();
/// "mesh", selector "type".
[[nodiscard]] const SectionDeclaration& fdm_mesh();
/// "material", selector "model" (or a "preset" the other keys override).
[[nodiscard]] const SectionDeclaration& fdm_material();
[[nodiscard]] const SectionDeclaration& fdm_damping();
/// One entry of "boundaries", selector "condition".
[[nodiscard]] const SectionDeclaration& fdm_boundary();
[[nodiscard]] const SectionDeclaration& fdm_initial_stress();
[[nodiscard]] const SectionDeclaration& fdm_coupling();

/// Largest longest/shortest zone edge a generated mesh may have unless
/// max_aspect_ratio says otherwise: FLAC practice keeps zones within about
/// 1:5 where accuracy matters; 10 leaves room for the outer, less important zones.
inline constexpr double kDefaultMaxAspectRatio = 10.0;

}  // namespace dfc::sections
