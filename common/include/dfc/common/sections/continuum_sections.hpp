#pragma once
// Declarations of the continuum_server section of a scenario (declaration.hpp):
// the axisymmetric continuum of the open-ended pile (docs/continuum_pile.md),
// read by continuum_server's parser (continuum_server/src/continuum_config.cpp),
// printed by its --help and published in scenario.schema.json.
#include "dfc/common/declaration.hpp"

namespace dfc::sections {

/// The whole configuration object of continuum_server (participants.<name>.config).
[[nodiscard]] const SectionDeclaration& continuum_server();
/// "mesh": the soil cylinder's structured triangle mesh.
[[nodiscard]] const SectionDeclaration& continuum_mesh();
/// "pile": the rigid open-ended pile and its interface friction.
[[nodiscard]] const SectionDeclaration& continuum_pile();
/// "initial_stress": uniform, held by the matching pressures on the top and the side.
[[nodiscard]] const SectionDeclaration& continuum_initial_stress();

}  // namespace dfc::sections
