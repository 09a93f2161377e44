#pragma once
// Stress servo of a periodic cell: each axis is either strain-rate controlled
// or stress controlled (docs/dem_periodic.md §4).
//
// The idea is PFC's wall servo (Itasca PFC "servo mechanism": wall velocity
// u = G (sigma_measured - sigma_required), G = alpha A / (k_n N_c dt), with a
// relaxation factor alpha < 1 for stability), written for a cell edge: the
// compressive strain increment that would remove the fraction `gain` of the
// stress error in one step if every contact deformed affinely is
//     d(eps_a) = gain (sigma_target - sigma_aa) / K_a,
// K_a the affine stiffness of the contacts in force (cell_stress.hpp). Since K_a
// bounds the true modulus from above (the packing relaxes non-affinely), the
// real correction per step is smaller: the loop is over-damped for gain <= 1.
// The edge strain rate (extension positive) is then
//     rate_a = -gain (sigma_target - sigma_aa) / (K_a dt),
// capped at |rate_a| <= max_strain_rate so that a loose packing (K_a ~ 0)
// closes at a bounded speed rather than in one step.
#include <array>

#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

enum class AxisMode {
  strain_rate,  ///< value: edge strain rate, 1/s, extension positive (0 holds the edge)
  stress,       ///< value: target normal stress, Pa, compression positive
};

struct AxisControl {
  AxisMode mode = AxisMode::strain_rate;
  double value = 0.0;
};

struct CellServo {
  std::array<AxisControl, 3> axes{};
  double gain = 0.5;              ///< alpha, the fraction of the stress error removed per step if the response were affine
  double max_strain_rate = 0.0;   ///< 1/s, cap of a stress-controlled axis (> 0)

  [[nodiscard]] bool controls_stress() const noexcept;
  /// Edge strain rates for the next step from the stress just measured.
  [[nodiscard]] Vec3 strain_rate(const CellStress& stress, double dt) const noexcept;
  /// Largest |sigma_target - sigma_aa| / sigma_target over the stress axes (0 without any).
  [[nodiscard]] double relative_error(const CellStress& stress) const noexcept;

  /// Isotropic consolidation: every axis held at `pressure` (Pa).
  [[nodiscard]] static CellServo isotropic(double pressure, double gain, double max_strain_rate);
  /// K0 (oedometric): lateral edges fixed, edge `axis` (0 x, 1 y, 2 z) stress controlled.
  [[nodiscard]] static CellServo k0(std::size_t axis, double vertical_stress, double gain, double max_strain_rate);
  /// Triaxial compression: edge `axis` shortens at `axial_rate` (1/s, > 0 compresses),
  /// the two others are held at the confining stress sigma3 (Pa).
  [[nodiscard]] static CellServo triaxial(std::size_t axis, double axial_rate, double sigma3, double gain, double max_strain_rate);
};

/// One step of the simulation under the servo: steps, measures the cell stress
/// and sets the cell's strain rate for the next step. Returns the stress.
CellStress servo_step(Simulation& simulation, const CellServo& servo, double dt);

}  // namespace dfc::dem
