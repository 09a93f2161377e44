#pragma once
// (c) 1-D column under gravity, K0 state (docs/theory/fdm.md §2(c)). Compression
// positive: σv = ρ g d, σh = K0 σv with K0 = ν/(1−ν), top settlement ρ g H²/(2M),
// M = K + 4G/3.
#include "dfc/fdm/verification/result.hpp"

namespace dfc::fdm::verification {

/// Relative tolerance of every row (§2 criterion for elastic problems, tightened to the 1 %; the reason is in problems.cpp).
inline constexpr double kGravityColumnTolerance = 0.01;

struct GravityColumnData {
  double height = 10.0;         ///< m
  double density = 2000.0;      ///< kg/m³
  double gravity = 9.81;        ///< m/s²
  double young_modulus = 5.0e7; ///< Pa
  double poisson_ratio = 0.3;
  [[nodiscard]] double vertical_stress(double depth) const { return density * gravity * depth; }
  [[nodiscard]] double k0() const { return poisson_ratio / (1.0 - poisson_ratio); }
  [[nodiscard]] double constrained_modulus() const;
  [[nodiscard]] double top_settlement() const;  ///< > 0 downwards, m
};

/// Level ℓ: a 1×1 m column of 11·2^ℓ − 1 zones (odd, so a centroid sits at mid-depth).
[[nodiscard]] ProblemResult run_gravity_column(int level);

}  // namespace dfc::fdm::verification
