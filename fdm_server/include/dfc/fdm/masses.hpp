#pragma once
// Gridpoint masses and the timestep limit (docs/theory/fdm.md §1.10).
#include <span>
#include <vector>

#include "dfc/fdm/tetrahedron.hpp"

namespace dfc::fdm {

/// Real (gravitational) lumped masses, kg: each tetrahedron gives ¼ of its mass
/// to each of its nodes, halved for two overlays (§1.10 "Dynamic").
[[nodiscard]] std::vector<double> lumped_masses(std::size_t gridpoint_count, std::span<const Tetrahedron> tetrahedra, double density);

/// Density-scaling coefficients c_l, kg/s², such that the inertial mass
///   m_l = c_l Δt²,   c_l = Σ_{t∋l} α₁/(9V⁽ᵗ⁾) maxᵢ (a_i⁽ˡ⁾)²,   α₁ = K + 4G/3
/// (§1.10 "Static", SNAC `Force.c`; a⁽ˡ⁾ = area vector of the face opposite l),
/// summed over both overlays without the ½ factor. With these masses any Δt is
/// stable: λ_max(M⁻¹K)Δt² ≈ 1 against the central-difference limit 4 (§1.10 check).
[[nodiscard]] std::vector<double> mass_scaling_coefficients(std::size_t gridpoint_count, std::span<const Tetrahedron> tetrahedra,
                                                            double p_wave_modulus);

/// The largest stable step with real masses, s: Δt_d = Δt_crit/2 with
/// Δt_crit = min_t V⁽ᵗ⁾/(C_p A_max⁽ᵗ⁾), C_p = √(α₁/ρ) (§1.10 "Dynamic").
[[nodiscard]] double critical_timestep(std::span<const Tetrahedron> tetrahedra, double p_wave_modulus, double density);

}  // namespace dfc::fdm
