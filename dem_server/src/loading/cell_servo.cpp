#include "dfc/dem/cell_servo.hpp"

#include <algorithm>
#include <cmath>

namespace dfc::dem {

namespace {
double diagonal(const CellStress& s, std::size_t a) noexcept { return s.sigma[a][a]; }
double stiffness(const CellStress& s, std::size_t a) noexcept {
  return a == 0 ? s.affine_stiffness.x : a == 1 ? s.affine_stiffness.y : s.affine_stiffness.z;
}
}  // namespace

bool CellServo::controls_stress() const noexcept {
  return std::any_of(axes.begin(), axes.end(), [](const AxisControl& c) { return c.mode == AxisMode::stress; });
}

Vec3 CellServo::strain_rate(const CellStress& stress, double dt) const noexcept {
  double rate[3] = {0.0, 0.0, 0.0};
  for (std::size_t a = 0; a < 3; ++a) {
    const AxisControl& c = axes[a];
    if (c.mode == AxisMode::strain_rate) {
      rate[a] = c.value;
      continue;
    }
    const double error = c.value - diagonal(stress, a);  // > 0: not compressed enough
    const double k = stiffness(stress, a);
    // No contact in force: close (or open) at the cap.
    const double wanted = k > 0.0 ? -gain * error / (k * dt) : (error > 0.0 ? -max_strain_rate : max_strain_rate);
    rate[a] = std::clamp(wanted, -max_strain_rate, max_strain_rate);
  }
  return {rate[0], rate[1], rate[2]};
}

double CellServo::relative_error(const CellStress& stress) const noexcept {
  double worst = 0.0;
  for (std::size_t a = 0; a < 3; ++a)
    if (axes[a].mode == AxisMode::stress) worst = std::max(worst, std::abs(axes[a].value - diagonal(stress, a)) / std::abs(axes[a].value));
  return worst;
}

CellServo CellServo::isotropic(double pressure, double gain, double max_strain_rate) {
  CellServo s{.gain = gain, .max_strain_rate = max_strain_rate};
  s.axes.fill({AxisMode::stress, pressure});
  return s;
}

CellServo CellServo::k0(std::size_t axis, double vertical_stress, double gain, double max_strain_rate) {
  CellServo s{.gain = gain, .max_strain_rate = max_strain_rate};
  s.axes.fill({AxisMode::strain_rate, 0.0});
  s.axes.at(axis) = {AxisMode::stress, vertical_stress};
  return s;
}

CellServo CellServo::triaxial(std::size_t axis, double axial_rate, double sigma3, double gain, double max_strain_rate) {
  CellServo s{.gain = gain, .max_strain_rate = max_strain_rate};
  s.axes.fill({AxisMode::stress, sigma3});
  s.axes.at(axis) = {AxisMode::strain_rate, -axial_rate};  // edge rate is extension positive
  return s;
}

CellStress servo_step(Simulation& sim, const CellServo& servo, double dt) {
  sim.step(dt);
  const CellStress stress = measure_cell_stress(sim);
  sim.set_cell_strain_rate(servo.strain_rate(stress, dt));
  return stress;
}

}  // namespace dfc::dem
