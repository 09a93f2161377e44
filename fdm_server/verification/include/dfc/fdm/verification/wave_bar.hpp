#pragma once
// (e) 1-D elastic wave in a laterally confined bar (docs/theory/fdm.md §2(e)): a
// velocity step v0 at one end sends a front at C_p = √(M/ρ), M = K + 4G/3,
// arriving at distance x at t = x/C_p, behind which σ = ρ C_p v0 and the
// particle velocity is v0.
#include "dfc/fdm/verification/result.hpp"

namespace dfc::fdm::verification {

/// Relative tolerance of every row (the 2 % on arrival and amplitude; the reason is in problems.cpp).
inline constexpr double kWaveBarTolerance = 0.02;

struct WaveBarData {
  double length = 10.0;         ///< m
  double station = 4.0;         ///< m from the loaded end
  double density = 2000.0;      ///< kg/m³
  double young_modulus = 5e7;   ///< Pa
  double poisson_ratio = 0.25;
  double velocity = 0.01;       ///< v0, m/s
  [[nodiscard]] double p_wave_speed() const;
  [[nodiscard]] double arrival_time() const { return station / p_wave_speed(); }
  [[nodiscard]] double stress_jump() const { return density * p_wave_speed() * velocity; }  ///< compressive, Pa
};

/// Level ℓ: 50·2^ℓ cubic zones along the bar, real masses, no damping, Δt = the
/// critical step (§1.10).
[[nodiscard]] ProblemResult run_wave_bar(int level);

}  // namespace dfc::fdm::verification
