#pragma once
// Large-strain expansion of a cylindrical or spherical cavity in an elastic–
// perfectly plastic Tresca material, in the form the solver integrates
// (Jaumann rate, logarithmic strain, constant bulk modulus): the derivation is
// docs/continuum_pile.md §7; for an incompressible material the cylinder is
// Gibson & Anderson (1961), and the limits are Yu & Houlsby's (1991) p_lim for
// φ = ψ = 0. Pressures compression positive.
namespace dfc::continuum {

enum class CavityGeometry { cylindrical, spherical };

struct TrescaCavity {
  CavityGeometry geometry = CavityGeometry::cylindrical;
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
/// Cavity pressure, Pa: cylinder p(a) = σ₀ + s_u [1 − c²/b² + 2 ln(c/a)],
/// sphere p(a) = σ₀ + s_u [4/3 (1 − c³/b³) + 4 ln(c/a)].
[[nodiscard]] double cavity_pressure(const TrescaCavity& cavity, double cavity_radius);
/// Limit pressure of an infinite medium, Pa: σ₀ + s_u [1 + ln(G/s_u)]
/// (cylinder), σ₀ + 4/3 s_u [1 + ln(G/s_u)] (sphere).
[[nodiscard]] double limit_pressure(const TrescaCavity& cavity);

}  // namespace dfc::continuum
