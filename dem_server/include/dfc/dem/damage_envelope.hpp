#pragma once
// The Zheng–Ciantia bond envelope and its closest-point return
// (docs/theory/dem_contact_laws.md §3.2, §3.5; Ciantia et al. 2024 Eq. 1; Zheng & Ciantia 2025).
//
// In normalised coordinates n = N/N̄ (signed), v = V/V̄ >= 0, m = |M̆|/M̃ >= 0:
//   f = m^1.001 + n² + v⁴ / (1 - n²) - 1,    elastic while f <= 0.
// f is convex (the v⁴/(1-n²) term has a positive-definite Hessian for |n| < 1),
// so the closest point of the admissible set to any trial point is unique.
//
// The return is associated plasticity: with the elastic "stiffness" diagonal
// in these coordinates (weights w, see damage_bond_law.hpp), the plastic
// increment is Δλ ∂f/∂x exactly when x is the point of {f <= 0} closest to
// the trial point in the metric Σ w_i (x_i - t_i)² (the energy norm;
// Simo & Hughes 1998, Computational Inelasticity, §3.3). The reference code
// minimises a Euclidean distance in (N, V, M̆) instead; the energy norm is
// the choice consistent with the associated flow rule it also states.
namespace dfc::dem {

struct EnvelopePoint {
  double n = 0.0;  ///< N / N̄, tension positive
  double v = 0.0;  ///< |V| / V̄ >= 0
  double m = 0.0;  ///< |M̆| / M̃ >= 0
};

struct ReturnWeights {
  double n = 1.0;
  double v = 1.0;
  double m = 1.0;
};

/// f of the envelope; +infinity where v > 0 and |n| >= 1 (outside the domain of the v⁴ term).
[[nodiscard]] double damage_envelope(const EnvelopePoint& x) noexcept;

/// damage_envelope(x) > 0, the same answer, mostly without its std::pow:
/// for |m| <= 1, |m|^1.001 <= |m|, so a point with h(n, v) + |m| below
/// 1 - 1e-12 is inside whatever pow returns (within an ulp of the exact
/// power). Why: the envelope check of every intact bond at every step spent
/// 21 % of a damage-bond run in std::pow (perf, the open-pile paper model).
[[nodiscard]] bool outside_damage_envelope(const EnvelopePoint& x) noexcept;

/// The point of {f <= 0} closest to `trial` in the weighted metric; `trial`
/// itself if it is admissible. The result satisfies -1e-12 <= f <= 0
/// (found by Illinois regula falsi on the Lagrange multiplier, each inner problem a convex
/// Newton solve), keeps the sign of n and has v <= trial.v, m <= trial.m.
[[nodiscard]] EnvelopePoint closest_admissible_point(const EnvelopePoint& trial, const ReturnWeights& weights) noexcept;

}  // namespace dfc::dem
