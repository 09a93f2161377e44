#pragma once
// Large-strain expansion of a cylindrical cavity in an elastic–perfectly
// plastic Tresca material, in the form the solver integrates (Jaumann rate,
// logarithmic strain, constant bulk modulus): the derivation is
// docs/continuum_pile.md §7; for an incompressible material it is Gibson &
// Anderson (1961), whose limit is Yu & Houlsby's (1991) p_lim for φ = ψ = 0.
// Pressures compression positive.
namespace dfc::continuum {

struct TrescaCavity {
  double shear_modulus = 0.0;        ///< G, Pa
  double bulk_modulus = 0.0;         ///< K, Pa
  double undrained_strength = 0.0;   ///< s_u, Pa
  double in_situ_pressure = 0.0;     ///< σ₀, Pa (isotropic, compression positive)
  double initial_radius = 0.0;       ///< a₀, m
  double outer_radius = 0.0;         ///< b, m: where the pressure σ₀ is held
};

/// Radius c of the plastic zone when the cavity radius is a (requires a
/// plastic zone, i.e. a beyond first yield); found by bisection on the mass
/// balance of the ring a ≤ r ≤ c.
[[nodiscard]] double plastic_radius(const TrescaCavity& cavity, double cavity_radius);
/// Cavity pressure p(a) = σ₀ + s_u [1 − c²/b² + 2 ln(c/a)], Pa.
[[nodiscard]] double cavity_pressure(const TrescaCavity& cavity, double cavity_radius);
/// Limit pressure σ₀ + s_u [1 + ln(G/s_u)] of an infinite medium, Pa.
[[nodiscard]] double limit_pressure(const TrescaCavity& cavity);

}  // namespace dfc::continuum
