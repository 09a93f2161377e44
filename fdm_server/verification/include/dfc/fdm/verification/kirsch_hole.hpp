#pragma once
// (a) Cylindrical hole in an infinite elastic medium under far-field stress
// (Kirsch; docs/theory/fdm.md §2(a), the Itasca test data). COMPRESSION POSITIVE,
// θ measured from the direction of p1:
//   σ_r = (p1+p2)/2 (1 − a²/r²) + (p1−p2)/2 (1 − 4a²/r² + 3a⁴/r⁴) cos2θ
//   σ_θ = (p1+p2)/2 (1 + a²/r²) − (p1−p2)/2 (1 + 3a⁴/r⁴) cos2θ
//   τ_rθ = −(p1−p2)/2 (1 + 2a²/r² − 3a⁴/r⁴) sin2θ
//   u_r = (p1+p2)/(4G) a²/r + (p1−p2)/(4G) a²/r [4(1−ν) − a²/r²] cos2θ   (towards the hole)
#include "dfc/fdm/verification/result.hpp"

namespace dfc::fdm::verification {

/// Relative tolerance of every row (between the §2 elastic (2 %) and near-hole (5 %) criteria; the reason is in problems.cpp).
inline constexpr double kKirschTolerance = 0.03;

struct KirschSolution {
  double radius = 1.0;      ///< a, m
  double p1 = 30e6;         ///< Pa, compressive, along the y axis in the fixture
  double p2 = 15e6;         ///< Pa, compressive, along the x axis
  double shear_modulus = 2.8e9;
  double bulk_modulus = 3.9e9;
  [[nodiscard]] double poisson_ratio() const;
  [[nodiscard]] double radial_stress(double r, double theta) const;
  [[nodiscard]] double hoop_stress(double r, double theta) const;
  [[nodiscard]] double shear_stress(double r, double theta) const;
  [[nodiscard]] double radial_displacement_towards_hole(double r, double theta) const;
};

/// Level ℓ: quarter annulus b = 6a, 12·2^ℓ zones radially and around, with the
/// closed-form traction on the outer boundary (so the truncation adds no error).
[[nodiscard]] ProblemResult run_kirsch_hole(int level);

}  // namespace dfc::fdm::verification
