#pragma once
// (d) Uniform pressure q on a disc of radius a on an elastic half-space
// (Boussinesq, integrated; docs/theory/fdm.md §2(d)). COMPRESSION POSITIVE, z is
// the depth below the surface, on the axis:
//   σ_z = q [1 − z³/(a²+z²)^{3/2}]
//   u_z = q/(2G) [2(1−ν)(√(a²+z²) − z) + z − z²/√(a²+z²)],   u_z(0) = 2qa(1−ν²)/E
// and the point-load field (P = q π a²), used far from the disc:
//   u_z = P/(4πGR) [2(1−ν) + z²/R²],  u_r = P/(4πGR) [rz/R² − (1−2ν) r/(R+z)].
#include "dfc/fdm/verification/result.hpp"
#include "dfc/fdm/types.hpp"

namespace dfc::fdm::verification {

/// Relative tolerance of every row (§2: 5 % near loads; the reason is in problems.cpp).
inline constexpr double kBoussinesqTolerance = 0.05;

struct BoussinesqSolution {
  double radius = 1.0;          ///< a, m
  double pressure = 1e5;        ///< q, Pa
  double young_modulus = 1e8;   ///< Pa
  double poisson_ratio = 0.3;
  [[nodiscard]] double shear_modulus() const { return young_modulus / (2.0 * (1.0 + poisson_ratio)); }
  [[nodiscard]] double axis_vertical_stress(double depth) const;
  [[nodiscard]] double axis_settlement(double depth) const;  ///< downwards, m
  /// Point-load displacement at horizontal distance r and depth z: (u_r outward, u_z downward), m.
  [[nodiscard]] Eigen::Vector2d point_load_displacement(double r, double depth) const;
};

/// Level ℓ: quarter box 6a × 6a × 6a, (16·2^ℓ)³ zones graded towards the load;
/// the far sides and the base get the point-load displacement.
[[nodiscard]] ProblemResult run_boussinesq_disc(int level);

}  // namespace dfc::fdm::verification
