#pragma once
// Mixed discretization (Marti & Cundall 1982; fdm-physics.md §1.5).
#include <span>

#include "dfc/fdm/types.hpp"

namespace dfc::fdm {

/// Replaces the volumetric part of each tetrahedron's strain rate by the
/// volume-weighted zone average over all tetrahedra of the zone (both overlays,
/// as SNAC `StrainRate.c` does):
///   ξ̄_kk = Σ ξ_kk⁽ᵗ⁾V⁽ᵗ⁾ / Σ V⁽ᵗ⁾,   ξ_ij⁽ᵗ⁾ ← ξ_ij⁽ᵗ⁾ + ⅓(ξ̄_kk − ξ_kk⁽ᵗ⁾)δ_ij.
/// Gives the zone the volumetric flexibility that constant-strain tetrahedra lack.
void apply_mixed_discretization(std::span<SymTensor> strain_rates, std::span<const double> volumes);

}  // namespace dfc::fdm
