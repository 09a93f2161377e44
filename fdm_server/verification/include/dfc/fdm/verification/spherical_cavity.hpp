#pragma once
// (g) Spherical cavity in an elastic–perfectly plastic Mohr–Coulomb medium
// (docs/theory/fdm.md §2(g)). COMPRESSION POSITIVE, cavity pressure p, in-situ p0,
// K_p = (1+sinφ)/(1−sinφ), Y = 2c√K_p:
//   elastic:     σ_r = p0 + (p−p0)(a/r)³,  σ_θ = p0 − ½(p−p0)(a/r)³,  u_r = (p−p0) a³/(4G r²)  (outward)
//   first yield: p_y = p0 + 2[(K_p−1) p0 + Y]/(K_p + 2)
#include "dfc/fdm/verification/result.hpp"

namespace dfc::fdm::verification {

/// Relative tolerance of every row (the 3 %; the reason is in problems.cpp).
inline constexpr double kSphericalCavityTolerance = 0.03;

struct SphericalCavitySolution {
  double radius = 1.0;           ///< a, m
  double in_situ = 2e6;          ///< p0, Pa
  double young_modulus = 1e9;    ///< Pa
  double poisson_ratio = 0.25;
  double cohesion = 1e6;         ///< Pa
  double friction_deg = 30.0;
  [[nodiscard]] double kp() const;
  [[nodiscard]] double shear_modulus() const { return young_modulus / (2.0 * (1.0 + poisson_ratio)); }
  [[nodiscard]] double first_yield_pressure() const;
  [[nodiscard]] double radial_stress(double r, double pressure) const;
  [[nodiscard]] double hoop_stress(double r, double pressure) const;
  [[nodiscard]] double radial_displacement(double r, double pressure) const;
};

/// Level ℓ: octant shell b = 5a, 12·2^ℓ zones radially, 6·2^ℓ per patch edge;
/// the cavity pressure is raised to 90 % of the way to first yield.
[[nodiscard]] ProblemResult run_spherical_cavity(int level);

}  // namespace dfc::fdm::verification
