#pragma once
// (f) Cylindrical hole in an infinite Mohr–Coulomb medium (Salençon 1969;
// docs/theory/fdm.md §2(f), the Itasca test data). COMPRESSION POSITIVE, with
// K_p = (1+sinφ)/(1−sinφ), q = 2c tan(45° + φ/2), K_ps = (1+sinψ)/(1−sinψ):
//   R0 = a [2/(K_p+1) (P0 + q/(K_p−1)) / (Pi + q/(K_p−1))]^{1/(K_p−1)},  σ_re = (2P0 − q)/(K_p+1)
//   plastic zone: σ_r = −q/(K_p−1) + (Pi + q/(K_p−1)) (r/a)^{K_p−1},  σ_θ = −q/(K_p−1) + K_p (…)(r/a)^{K_p−1}
//   elastic zone: σ_r,θ = P0 ∓ (P0 − σ_re)(R0/r)²,  u_r = −(P0 − σ_re) R0²/(2G r)   (outward positive)
//   plastic-zone u_r: the §2(f) expression (checked there against direct integration).
#include "dfc/fdm/verification/result.hpp"

namespace dfc::fdm::verification {

/// Relative tolerance of every row (§2: R0 and the wall displacement within 3–5 %; the stricter end; the reason is in problems.cpp).
inline constexpr double kSalenconTolerance = 0.03;

struct SalenconSolution {
  double radius = 1.0;            ///< a, m
  double in_situ = 30e6;          ///< P0, Pa
  double internal = 0.0;          ///< Pi, Pa
  double shear_modulus = 2.8e9;   ///< Pa
  double bulk_modulus = 3.9e9;    ///< Pa
  double cohesion = 3.45e6;       ///< Pa
  double friction_deg = 30.0;
  double dilation_deg = 0.0;
  [[nodiscard]] double kp() const;
  [[nodiscard]] double kps() const;
  [[nodiscard]] double q() const;   ///< 2c tan(45° + φ/2), Pa
  [[nodiscard]] double poisson_ratio() const;
  [[nodiscard]] double plastic_radius() const;       ///< R0, m
  [[nodiscard]] double interface_stress() const;     ///< σ_re, Pa
  [[nodiscard]] double radial_stress(double r) const;  ///< Pa
  [[nodiscard]] double hoop_stress(double r) const;    ///< Pa
  [[nodiscard]] double radial_displacement(double r) const;  ///< m, outward positive
};

/// Level ℓ = 0, 1, 2: quarter annulus b = 5a with 24, 32, 48 zones radially and
/// around; ψ = 0°, and from level 1 also ψ = 30°.
[[nodiscard]] ProblemResult run_salencon_hole(int level);

}  // namespace dfc::fdm::verification
