#pragma once
// (b) Thick-walled cylinder under internal pressure, plane strain (Lamé;
// docs/theory/fdm.md §2(b)). Tension positive: σ_r = A − B/r², σ_θ = A + B/r²,
// A = (p_i a² − p_o b²)/(b² − a²), B = (p_i − p_o) a² b²/(b² − a²),
// u_r = r/(2G) [(1−2ν) A + B/r²].
// With the outer wall held radially instead (u_r(b) = 0, outer_wall_held):
// σ_r(a) = −p_i and u_r(b) = 0 give A = −p_i / (1 + (1−2ν) b²/a²),
// B = −(1−2ν) A b² (same σ_r, σ_θ, u_r expressions).
#include "dfc/fdm/verification/result.hpp"

namespace dfc::fdm::verification {

/// Relative tolerance of every row (§2: 1–2 % for elastic problems away from singular points; the reason is in problems.cpp).
inline constexpr double kLameTolerance = 0.02;

struct LameSolution {
  double inner_radius = 1.0;   ///< a, m
  double outer_radius = 3.0;   ///< b, m
  double inner_pressure = 1e7; ///< p_i, Pa
  double outer_pressure = 0.0; ///< p_o, Pa
  double young_modulus = 1e9;  ///< Pa
  double poisson_ratio = 0.25;
  bool outer_wall_held = false;  ///< true: u_r(b) = 0 (radial roller) and outer_pressure unused
  [[nodiscard]] double a_coefficient() const;
  [[nodiscard]] double b_coefficient() const;
  [[nodiscard]] double radial_stress(double r) const;  ///< Pa, tension positive
  [[nodiscard]] double hoop_stress(double r) const;    ///< Pa, tension positive
  [[nodiscard]] double radial_displacement(double r) const;  ///< m, outward positive
};

/// Level ℓ: quarter annulus b = 3a with 8·2^ℓ zones radially and around.
[[nodiscard]] ProblemResult run_lame_cylinder(int level);

}  // namespace dfc::fdm::verification
