#include "dfc/constitutive/mohr_coulomb_model.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "dfc/common/config_reader.hpp"
#include "dfc/common/errors.hpp"

namespace dfc::constitutive {

namespace {

constexpr std::array<std::string_view, MohrCoulombModel::kStateSize> kStateNames = {
    "plastic_shear_strain",    // Σ Δε^ps (§4, strain-softening measure), -
    "plastic_tensile_strain",  // Σ Δε3^p of tension corrections, -
    "failure_now",             // 0 elastic, 1 shear, 2 tension in the last update
};

// Principal plastic strain of a correction: Δε^p = C (σ^I − σ^N), C the
// elastic compliance in principal space (the correction is the stress that
// the plastic strain relaxes).
Vec3 principal_plastic_strain(const Vec3& stress_drop, const ElasticModuli& m) {
  const double young = 9.0 * m.bulk * m.shear / (3.0 * m.bulk + m.shear);
  const double poisson = (3.0 * m.bulk - 2.0 * m.shear) / (2.0 * (3.0 * m.bulk + m.shear));
  const double sum = stress_drop.sum();
  return (stress_drop * (1.0 + poisson) - Vec3::Constant(poisson * sum)) / young;
}

// The plastic shear strain increment of the FLAC strain-softening model (§4,
// last paragraph; unconfirmed there, used here only as a monitor):
// Δε^ps = (1/√2) √[(Δε1 − Δε_m)² + Δε_m² + (Δε3 − Δε_m)²], Δε_m = (Δε1 + Δε3)/3.
double plastic_shear_increment(const Vec3& e) {
  const double mean = (e.x() + e.z()) / 3.0;
  return std::sqrt((e.x() - mean) * (e.x() - mean) + mean * mean + (e.z() - mean) * (e.z() - mean)) / std::sqrt(2.0);
}

}  // namespace

MohrCoulombModel::MohrCoulombModel(ElasticModuli moduli, const MohrCoulombStrength& strength)
    : moduli_(moduli), strength_(strength), constants_(MohrCoulombConstants::from(strength, moduli)) {
  if (!(strength.cohesion >= 0.0)) throw UserError("mohr_coulomb: cohesion_pa must be >= 0");
  if (!(strength.friction_angle_deg >= 0.0 && strength.friction_angle_deg < 90.0))
    throw UserError("mohr_coulomb: friction_angle_deg must be in [0, 90)");
  if (!(strength.dilation_angle_deg >= 0.0 && strength.dilation_angle_deg <= strength.friction_angle_deg))
    throw UserError("mohr_coulomb: dilation_angle_deg must be in [0, friction_angle_deg] (FLAC's admissible range)");
  if (!(strength.tensile_strength >= 0.0)) throw UserError("mohr_coulomb: tensile_strength_pa must be >= 0");
}

std::unique_ptr<ConstitutiveModel> MohrCoulombModel::from_config(ConfigReader& material) {
  const ElasticModuli moduli = read_elastic_moduli(material);
  MohrCoulombStrength strength;
  strength.cohesion = material.number("cohesion_pa");
  strength.friction_angle_deg = material.number("friction_angle_deg");
  if (!(strength.friction_angle_deg < 90.0)) material.fail("friction_angle_deg", "expected an angle in [0, 90) degrees, got 90");
  strength.dilation_angle_deg = material.number("dilation_angle_deg");
  if (strength.dilation_angle_deg > strength.friction_angle_deg)
    material.fail("dilation_angle_deg", "must not exceed friction_angle_deg (" + std::to_string(strength.friction_angle_deg) +
                                            "); FLAC's admissible range is 0 <= psi <= phi");
  strength.tensile_strength = material.number("tensile_strength_pa");
  return std::make_unique<MohrCoulombModel>(moduli, strength);
}

std::span<const std::string_view> MohrCoulombModel::state_names() const { return kStateNames; }

double MohrCoulombModel::shear_function(const Stress& stress) const {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(stress.matrix(), Eigen::EigenvaluesOnly);
  return mohr_coulomb_shear_function(eigen.eigenvalues(), constants_);
}

void MohrCoulombModel::update(const StrainIncrement& increment, Stress& stress, StateSpan state) const {
  stress += elastic_stress_increment(moduli_, increment.strain);  // elastic trial σ^I
  state[kFailureNow] = 0.0;
  // Cheap check first: most tetrahedra are elastic, and eigenvalues alone
  // (ascending: σ1 <= σ2 <= σ3) decide that.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(stress.matrix(), Eigen::EigenvaluesOnly);
  const Vec3 trial = eigen.eigenvalues();
  const PrincipalReturn corrected = mohr_coulomb_return(trial, constants_);
  if (corrected.failure == MohrCoulombFailure::none) return;

  // §4 "Return to global axes": keep the trial's principal directions and add
  // the principal corrections, σ = σ^I + Σ_k (σ_k^N − σ_k^I) e_k ⊗ e_k.
  eigen.computeDirect(stress.matrix(), Eigen::ComputeEigenvectors);
  const Vec3 change = corrected.stress - eigen.eigenvalues();
  const Eigen::Matrix3d& e = eigen.eigenvectors();
  stress += SymTensor::symmetric_part(e * change.asDiagonal() * e.transpose());

  const Vec3 plastic = principal_plastic_strain(-change, moduli_);
  if (corrected.failure == MohrCoulombFailure::shear) {
    state[kPlasticShearStrain] += plastic_shear_increment(plastic);
  } else {
    state[kPlasticTensileStrain] += std::max(0.0, plastic.z());
  }
  state[kFailureNow] = double(corrected.failure);
}

}  // namespace dfc::constitutive
