#pragma once
// Element tests without a mesh: integrates a constitutive model at one
// material point along laboratory paths (drained triaxial, oedometer, or any
// strain path), the way the model is called by the solver (§1.6: a strain
// increment and the current stress, history per point). Used for the model
// tests and for calibration. Tension positive, like the solver.
#include <span>
#include <vector>

#include "dfc/constitutive/constitutive_model.hpp"

namespace dfc::constitutive {

class MaterialPointDriver {
 public:
  /// Starts at `initial_stress` with the model's initial history for it.
  MaterialPointDriver(const ConstitutiveModel& model, const Stress& initial_stress);

  /// Strain-controlled step: the full increment is prescribed.
  void strain_step(const SymTensor& increment);
  /// Oedometer (1-D compression along z): only ε_zz changes.
  void oedometer_step(double axial_strain_increment);
  /// Drained triaxial along z: ε_zz changes by `axial_strain_increment`
  /// (< 0 compresses), the lateral stresses σ_xx and σ_yy stay at their values
  /// before the step and the shear strains stay zero. The lateral strains are
  /// found by Newton's method with a finite-difference Jacobian of the model.
  /// Throws dfc::SolverError if the lateral stresses cannot be held.
  void triaxial_step(double axial_strain_increment);

  [[nodiscard]] const Stress& stress() const { return stress_; }
  [[nodiscard]] const SymTensor& strain() const { return strain_; }  ///< total strain, extension positive
  [[nodiscard]] std::span<const double> state() const { return state_; }
  /// Compression-positive invariants of the current stress.
  [[nodiscard]] double mean_pressure() const { return -stress_.trace() / 3.0; }
  [[nodiscard]] double deviatoric_stress() const;
  /// Compression-positive volumetric strain −tr ε.
  [[nodiscard]] double volumetric_strain() const { return -strain_.trace(); }

 private:
  /// The stress after `increment` from the current state, without committing it.
  [[nodiscard]] Stress trial(const SymTensor& increment) const;

  const ConstitutiveModel& model_;
  Stress stress_;
  SymTensor strain_;
  std::vector<double> state_;
};

}  // namespace dfc::constitutive
