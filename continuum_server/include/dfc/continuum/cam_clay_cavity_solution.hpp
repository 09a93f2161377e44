#pragma once
// Undrained large-strain expansion of a cylindrical or spherical cavity in
// Modified Cam clay, semi-analytical: the reference of the Cam clay cavity
// test (docs/continuum_pile.md §7.1). The approach is that of Collins & Yu
// (1996) and Cao, Teh & Chang (2001): undrained means isochoric, so every
// material point's deformation is fixed by its hoop strain ε = ln(r/r₀)
// alone, each point follows the same effective stress path (integrated here
// from the constitutive rates at constant volume), and the cavity pressure is
// the radial equilibrium integrated over ε by quadrature. The material is the
// one the shared model implements (structured_cam_clay with p_t = 0, ξ_s = 0,
// M_f = M_g = M), which differs from those papers' in one respect: linear
// elasticity with constant K and G (their κ-law has K ∝ p′); so the published
// numbers do not apply, the method does. Stresses compression positive.
#include "dfc/continuum/tresca_cavity_closed_form.hpp"  // CavityGeometry

namespace dfc::continuum {

struct CamClayCavity {
  CavityGeometry geometry = CavityGeometry::cylindrical;
  double shear_modulus = 0.0;               ///< G, Pa
  double bulk_modulus = 0.0;                ///< K of the skeleton, Pa
  double critical_state_ratio = 0.0;        ///< M (the model's M_f = M_g)
  /// ρ of p_c = p_c0 exp(ρ ε_v^p), ε_v^p the plastic volumetric strain
  /// (compression positive): v/(λ − κ) in Cam clay's terms, the model's ρ_s.
  double hardening_rate = 0.0;
  double in_situ_effective_pressure = 0.0;  ///< p₀′, Pa (isotropic)
  double preconsolidation_pressure = 0.0;   ///< p_c0 ≥ p₀′, Pa: OCR = p_c0/p₀′
  double in_situ_pore_pressure = 0.0;       ///< u₀, Pa; the total σ₀ = p₀′ + u₀ is held at b
  double initial_radius = 0.0;              ///< a₀, m
  /// b₀, m: where the total pressure σ₀ is held (it moves with the soil);
  /// infinity for an infinite medium.
  double outer_radius = 0.0;
};

/// A material point's state on the undrained path.
struct CamClayPathState {
  double mean_effective_stress = 0.0;      ///< p′, Pa
  double deviatoric_stress = 0.0;          ///< q, Pa
  double preconsolidation_pressure = 0.0;  ///< p_c, Pa
  double plastic_volumetric_strain = 0.0;  ///< ε_v^p = −ε_v^e (isochoric), compression positive
};

/// The state of a point whose hoop strain is ln(r/r₀) = `hoop_strain` ≥ 0.
[[nodiscard]] CamClayPathState undrained_path_state(const CamClayCavity& cavity, double hoop_strain);
/// Total cavity pressure (the radial stress at the wall), Pa, at cavity radius a ≥ a₀.
[[nodiscard]] double cavity_pressure(const CamClayCavity& cavity, double cavity_radius);
/// Excess pore pressure, Pa, at the current radius r (a ≤ r ≤ b) when the
/// cavity radius is a: the total mean stress there less p′ and u₀.
[[nodiscard]] double excess_pore_pressure(const CamClayCavity& cavity, double cavity_radius, double radius);
/// Limit pressure of an infinite medium (a/a₀ → ∞, b → ∞), Pa.
[[nodiscard]] double limit_pressure(const CamClayCavity& cavity);

}  // namespace dfc::continuum
