#pragma once
// Declarations of the DEM's contact laws (declaration.hpp): the "contact"
// object of the dem_server section, selector "law". Each law's keys are
// declared once here, in the order its factory reads them; the DEM's
// contact-law registry (dem_server/src/laws/contact_law_registry.cpp) builds
// laws from these named values, --help prints them, and upscaling by S
// multiplies each by S^upscaling_exponent (Thakur et al. 2015: contact
// stiffness scales with particle size; dimensionless ratios stay fixed).
#include "dfc/common/declaration.hpp"

namespace dfc::sections {

/// {"law": keyword (default "linear"), <the law's keys>}.
[[nodiscard]] const SectionDeclaration& dem_contact();
[[nodiscard]] const SectionDeclaration& linear_law();
[[nodiscard]] const SectionDeclaration& linear_pbond_law();
[[nodiscard]] const SectionDeclaration& soft_bond_law();
[[nodiscard]] const SectionDeclaration& damage_bond_law();

}  // namespace dfc::sections
