#include "dfc/constitutive/material_point_driver.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "dfc/common/errors.hpp"

namespace dfc::constitutive {

namespace {

// The lateral stresses are held to this fraction of the stress magnitude
// (round-off of the model's update is ~1e-15 of it).
constexpr double kStressTolerance = 1e-11;
constexpr int kMaxIterations = 50;

}  // namespace

MaterialPointDriver::MaterialPointDriver(const ConstitutiveModel& model, const Stress& initial_stress)
    : model_(model), stress_(initial_stress), state_(model.state_size(), 0.0) {
  model_.initialize_state(stress_, state_);
}

double MaterialPointDriver::deviatoric_stress() const { return std::sqrt(1.5) * stress_.deviator().norm(); }

Stress MaterialPointDriver::trial(const SymTensor& increment) const {
  Stress stress = stress_;
  std::vector<double> state = state_;
  model_.update(StrainIncrement{increment}, stress, state);
  return stress;
}

void MaterialPointDriver::strain_step(const SymTensor& increment) {
  model_.update(StrainIncrement{increment}, stress_, state_);
  strain_ += increment;
}

void MaterialPointDriver::oedometer_step(double axial_strain_increment) {
  strain_step(SymTensor{0.0, 0.0, axial_strain_increment, 0.0, 0.0, 0.0});
}

void MaterialPointDriver::triaxial_step(double axial_strain_increment) {
  const Eigen::Vector2d target(stress_.xx, stress_.yy);
  const double scale = std::max(stress_.norm(), 1.0);
  // Elastic first guess: zero lateral stress increments with α1 = K + 4G/3, α2 = K − 2G/3.
  const ElasticModuli m = model_.stiffest_moduli();
  const double alpha1 = m.bulk + 4.0 * m.shear / 3.0;
  const double alpha2 = m.bulk - 2.0 * m.shear / 3.0;
  Eigen::Vector2d lateral = Eigen::Vector2d::Constant(-alpha2 / (alpha1 + alpha2) * axial_strain_increment);
  const auto increment = [&](const Eigen::Vector2d& e) { return SymTensor{e.x(), e.y(), axial_strain_increment, 0.0, 0.0, 0.0}; };
  const auto residual = [&](const Eigen::Vector2d& e) {
    const Stress s = trial(increment(e));
    return Eigen::Vector2d(s.xx - target.x(), s.yy - target.y());
  };
  const double perturbation = 1e-7 * std::max(std::abs(axial_strain_increment), 1e-12);
  Eigen::Vector2d r = residual(lateral);
  for (int iteration = 0; iteration < kMaxIterations && r.norm() > kStressTolerance * scale; ++iteration) {
    Eigen::Matrix2d jacobian;
    for (int c = 0; c < 2; ++c) {
      Eigen::Vector2d shifted = lateral;
      shifted[c] += perturbation;
      jacobian.col(c) = (residual(shifted) - r) / perturbation;
    }
    lateral -= jacobian.fullPivLu().solve(r);
    r = residual(lateral);
  }
  if (r.norm() > kStressTolerance * scale * 1e3)
    throw SolverError("triaxial step: the lateral stresses could not be held (residual " + std::to_string(r.norm()) +
                      " Pa); use a smaller axial strain increment");
  strain_step(increment(lateral));
}

}  // namespace dfc::constitutive
