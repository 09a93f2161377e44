#pragma once
// Triaxial compression of a cuboid sample between six rigid plane walls: two
// platens and two opposite pairs of lateral walls (docs/dem_triaxial_walls.md).
//
// This is PFC's rigid-wall triaxial test (Itasca PFC "servo mechanism";
// Potyondy & Cundall 2004 §3.1): the lateral walls are servo-controlled to the
// confining stress sigma_3 while the platens close at a constant strain rate.
// Every wall stays a rigid plane that only translates along its own normal.
//
// Geometry (vertex centroids c_k of the walls, directions fixed at set-up):
//   axis a           unit, bottom platen -> top platen;  H   = (c_top - c_bottom) . a
//   lateral axis b_p unit, first -> second wall of pair p; W_p = (c_second - c_first) . b_p
// Stress on wall k (compression positive): sigma_k = (F_k . o_k) / A_k, with F_k
// the force the particles exert ON the wall, o_k its outward direction (+a for
// the top, -a for the bottom, -b_p / +b_p for the first / second of pair p) and
// A_k its current loaded area (W_0 W_1 for a platen, H W_other for a lateral wall).
//
// Servo (PFC's form, per wall): in one step a wall moving inwards at speed u
// raises its stress by about k_n N_c u dt / A_k (N_c contacts in force, k_n
// their normal stiffness), so the speed that removes the fraction `gain` of the
// stress error in one step is
//     u_k = gain A_k (sigma_target - sigma_k) / (k_n N_c dt),
// with k_n the wall law's stiffness bound (the real stiffness is lower, so the
// loop is over-damped for gain <= 1), and |u_k| capped at half the largest strain
// rate times the sample extent along o_k (both walls of a pair move).
#include <array>
#include <cstddef>
#include <optional>
#include <span>

#include "dfc/dem/dem_engine.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

/// The six walls, as indices into Simulation::walls().
struct TriaxialWalls {
  std::size_t top = 0;
  std::size_t bottom = 0;
  std::array<std::size_t, 4> lateral{};  ///< {first, second} of pair 0, then of pair 1
  /// top, bottom, lateral[0..3]: the order of BoxStress and BoxVertices.
  [[nodiscard]] std::array<std::size_t, 6> in_order() const noexcept { return {top, bottom, lateral[0], lateral[1], lateral[2], lateral[3]}; }
};

/// Directions of the box, fixed at set-up.
struct BoxAxes {
  Vec3 axis;                    ///< unit, bottom -> top
  std::array<Vec3, 2> lateral;  ///< unit, first -> second wall of each pair
};

/// Current dimensions of the box along its axes.
struct BoxSize {
  double height = 0.0;                ///< m, platen separation H
  std::array<double, 2> width{};      ///< m, lateral separations W_0, W_1
  [[nodiscard]] double volume() const noexcept { return height * width[0] * width[1]; }
};

/// Per-wall stresses, Pa, compression positive; wall order top, bottom, then lateral[0..3].
struct BoxStress {
  std::array<double, 6> wall{};
  [[nodiscard]] double axial() const noexcept { return 0.5 * (wall[0] + wall[1]); }
  /// Mean of the four lateral walls (sigma_3).
  [[nodiscard]] double lateral() const noexcept { return 0.25 * (wall[2] + wall[3] + wall[4] + wall[5]); }
  [[nodiscard]] double deviator() const noexcept { return axial() - lateral(); }
};

/// Vertices of the six walls in the order top, bottom, lateral[0..3].
using BoxVertices = std::array<std::span<const Vec3>, 6>;
[[nodiscard]] BoxVertices box_vertices(std::span<const Wall> walls, const TriaxialWalls& box);

/// Axes of the box from the walls' vertex centroids; throws UserError if two
/// opposite walls coincide or the three directions are not mutually
/// perpendicular within 1e-6 rad.
[[nodiscard]] BoxAxes box_axes(const BoxVertices& vertices);
[[nodiscard]] BoxSize box_size(std::span<const Wall> walls, const TriaxialWalls& box, const BoxAxes& axes);
/// Stresses from the walls' forces of the last step.
[[nodiscard]] BoxStress box_stress(std::span<const Wall> walls, const TriaxialWalls& box, const BoxAxes& axes, const BoxSize& size);

/// What drives the walls: every wall at the confining stress, or (axial strain
/// rate given) the platens at constant speed and the lateral walls at sigma_3.
struct TriaxialControl {
  double confining_stress = 0.0;         ///< Pa, sigma_3 (> 0)
  double gain = 0.5;                     ///< fraction of the stress error removed per step if the stiffness were k_n N_c
  double max_strain_rate = 0.0;          ///< 1/s, cap of a stress-controlled wall pair
  std::optional<double> platen_speed;    ///< m/s, each platen towards the other; none: platens stress-controlled too
};

/// One step under the control: steps the body, measures the stresses and
/// sets every wall's velocity for the next step (the same on every process of
/// a decomposed body: the wall loads and the counts are the whole body's).
/// Returns the stresses measured.
BoxStress triaxial_step(DemEngine& engine, const TriaxialWalls& box, const BoxAxes& axes, const TriaxialControl& control, double dt);

/// 1 - sphere volume / box volume.
[[nodiscard]] double box_porosity(const ParticleStore& particles, const BoxSize& size) noexcept;
/// 1 - solid_volume / box volume.
[[nodiscard]] double box_porosity(double solid_volume, const BoxSize& size) noexcept;

/// Largest |sigma_target - sigma_k| / sigma_target over the stress-controlled walls.
[[nodiscard]] double confinement_error(const BoxStress& stress, const TriaxialControl& control) noexcept;

}  // namespace dfc::dem
