#pragma once
// Terzaghi's one-dimensional consolidation (Terzaghi 1943, Theoretical Soil
// Mechanics, Wiley, doi:10.1002/9780470172766): a layer of thickness H drained
// at one face and impermeable at the other, loaded at t = 0 by a constant
// vertical stress that raises the pore pressure uniformly to p₀. With
// T = c_v t / H² and z the distance from the drained face,
//   p(z, T)/p₀ = Σ_{m≥0} (2/M) sin(M z/H) exp(−M² T),   M = (2m + 1) π/2,
//   U(T) = 1 − Σ_{m≥0} (2/M²) exp(−M² T)   (degree of consolidation).
// With a compressible fluid and the skeleton's constrained modulus E_oed
// (Biot 1941, doi:10.1063/1.1712886), from the undrained balance
// p₀/M_w = −α ε_v and q = E_oed (−ε_v) + α p₀:
//   p₀ = α q M_w / (E_oed + α² M_w),   c_v = (k/γ_w) / (1/M_w + α²/E_oed).
namespace dfc::continuum {

/// p/p₀ at depth ratio z/H (0 at the drained face) and time factor T ≥ 0.
[[nodiscard]] double terzaghi_pressure_ratio(double depth_ratio, double time_factor);
/// U(T), the settlement gained over its final value (1 − the mean p/p₀).
[[nodiscard]] double terzaghi_degree_of_consolidation(double time_factor);

/// The 1-D Biot column's constants.
struct OedometricBiotColumn {
  double constrained_modulus = 0.0;  ///< E_oed = K + 4G/3 of the skeleton, Pa
  double biot_modulus = 0.0;         ///< M_w, Pa
  double biot_coefficient = 1.0;     ///< α
  double mobility = 0.0;             ///< k/γ_w, m²/(Pa s)

  /// Pore pressure right after a load step q (undrained, no lateral strain), Pa.
  [[nodiscard]] double undrained_pore_pressure(double load) const;
  /// c_v, m²/s.
  [[nodiscard]] double consolidation_coefficient() const;
};

}  // namespace dfc::continuum
