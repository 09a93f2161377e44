#pragma once
// Average stress in a periodic cell by the Love–Weber formula, and the affine
// stiffness the stress servo takes its gain from (docs/dem_periodic.md §3).
//
//   sigma_ab = -(1/V) sum_c f_a d_b          (Love 1927; Weber 1966; e.g.
//                                              Christoffersen, Mehrabadi & Nemat-Nasser 1981)
// over the particle–particle contacts c, with f the contact force on the
// first particle and d = x_second - x_first the branch vector between the
// centres (minimum image). The minus sign makes COMPRESSION POSITIVE, the
// soil-mechanics convention of every cell_stress_* monitor: a repulsive
// contact pushes the first particle along -d. Contact couples (bond moments)
// enter only through the forces; the dynamic term -(1/V) sum m v v is left
// out (quasi-static samples). Wall contacts are not counted: the cell stress
// is that of the periodic particle skeleton.
#include <array>

#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct CellStress {
  std::array<std::array<double, 3>, 3> sigma{};  ///< Pa, compression positive
  /// Pa, d sigma_aa / d(compressive strain_aa) if every contact in force
  /// followed the affine motion: (1/V) sum_c k_n d_a^2 n_a^2 with k_n the law's
  /// normal stiffness bound (an upper bound of the true modulus, so a servo
  /// gain taken from it errs on the stable side); c runs over the contacts in
  /// force and every bond (intact or damaged), loaded or not.
  Vec3 affine_stiffness;

  [[nodiscard]] double mean() const noexcept { return (sigma[0][0] + sigma[1][1] + sigma[2][2]) / 3.0; }
  [[nodiscard]] Vec3 diagonal() const noexcept { return {sigma[0][0], sigma[1][1], sigma[2][2]}; }
};

/// Stress of the last force evaluation at the current positions. Serial sum in
/// contact order: the same bits for every thread count. Needs a periodic cell.
[[nodiscard]] CellStress measure_cell_stress(const Simulation& simulation);

/// 1 - (sum of sphere volumes) / cell volume (overlaps are not subtracted:
/// the convention of PFC's porosity of a radius-expanded sample).
[[nodiscard]] double cell_porosity(const ParticleStore& particles, const PeriodicCell& cell);

}  // namespace dfc::dem
