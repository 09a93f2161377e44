#pragma once
// Mixed discretization (Marti & Cundall 1982; docs/theory/fdm.md §1.5).
#include <span>

#include "dfc/fdm/types.hpp"

namespace dfc::fdm {

/// Replaces the volumetric part of each tetrahedron's strain rate by the
/// volume-weighted zone average over all tetrahedra of the zone (both overlays,
/// as SNAC `StrainRate.c` does):
///   ξ̄_kk = Σ ξ_kk⁽ᵗ⁾V⁽ᵗ⁾ / Σ V⁽ᵗ⁾,   ξ_ij⁽ᵗ⁾ ← ξ_ij⁽ᵗ⁾ + ⅓(ξ̄_kk − ξ_kk⁽ᵗ⁾)δ_ij.
/// Gives the zone the volumetric flexibility that constant-strain tetrahedra lack.
void apply_mixed_discretization(std::span<SymTensor> strain_rates, std::span<const double> volumes);

/// The same averaging applied to the stress after the constitutive call, for
/// models with plastic volume change (§1.5: "similar loops (based on stress)
/// are used, after calling the constitutive model"). Each tetrahedron's
/// mean-stress increment Δσ_m⁽ᵗ⁾ = σ_m⁽ᵗ⁾ − old_means[t] is replaced by the
/// volume-weighted zone average:
///   σ⁽ᵗ⁾ ← σ⁽ᵗ⁾ + (Δσ̄_m − Δσ_m⁽ᵗ⁾) I.
/// Averaging the increment (not the mean stress itself) leaves equal elastic
/// increments untouched, so only the differing plastic parts are averaged, as
/// the Itasca SDK's "mean plastic stress change" (`pore_pressure_increment_`) implies.
void apply_mean_stress_mixed_discretization(std::span<SymTensor> stresses, std::span<const double> old_means,
                                            std::span<const double> volumes);

}  // namespace dfc::fdm
