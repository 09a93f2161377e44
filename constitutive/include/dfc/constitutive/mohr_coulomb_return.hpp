#pragma once
// The FLAC Mohr–Coulomb return mapping in principal stress space
// (docs/theory/fdm.md §4; Itasca SDK `modelmohr.cpp`). Tension positive, principal
// stresses ordered σ1 <= σ2 <= σ3 (σ1 the most compressive).
//
//   shear:    F_s = N_φ σ3 − σ1 − 2c√N_φ > 0 fails; potential g_s = σ1 − N_ψ σ3 (non-associated)
//   tension:  f_t = σ3 − σ_t > 0 fails;           potential g_t = −σ3 (associated)
//
// These are pure functions of the trial principal stresses; the model class
// (mohr_coulomb_model.hpp) does the spectral decomposition and keeps history.
#include "dfc/constitutive/constitutive_model.hpp"

namespace dfc::constitutive {

/// Strength parameters as the user gives them.
struct MohrCoulombStrength {
  double cohesion = 0.0;            ///< c, Pa, >= 0
  double friction_angle_deg = 0.0;  ///< φ, degrees, in [0, 90)
  double dilation_angle_deg = 0.0;  ///< ψ, degrees, in [0, φ]
  double tensile_strength = 0.0;    ///< σ_t, Pa, >= 0 (capped at the apex c/tanφ)
};

/// The constants of the return mapping, computed once per material
/// (`updateParameters` of the Itasca code).
struct MohrCoulombConstants {
  double n_phi = 1.0;             ///< N_φ = (1+sinφ)/(1−sinφ)
  double n_psi = 1.0;             ///< N_ψ
  double two_c_sqrt_n_phi = 0.0;  ///< 2c√N_φ
  double distance_scale = 1.0;    ///< √(1+N_φ²): F_s / this = distance to the shear line
  double tension = 0.0;           ///< σ_t after the apex cap
  double apex = 0.0;              ///< c/tanφ; +∞ when φ = 0
  double alpha1 = 0.0;            ///< K + 4G/3
  double alpha2 = 0.0;            ///< K − 2G/3
  Vec3 shear_factors = Vec3::Zero();  ///< (sc1, sc2, sc3): σ_k += F_s sc_k in a shear correction

  [[nodiscard]] static MohrCoulombConstants from(const MohrCoulombStrength& strength, const ElasticModuli& moduli);
};

enum class MohrCoulombFailure { none = 0, shear = 1, tension = 2 };

struct PrincipalReturn {
  Vec3 stress = Vec3::Zero();  ///< corrected principal stresses σ1, σ2, σ3 (same directions)
  MohrCoulombFailure failure = MohrCoulombFailure::none;
};

/// Shear yield function F_s = N_φ σ3 − σ1 − 2c√N_φ (> 0: failure).
[[nodiscard]] double mohr_coulomb_shear_function(const Vec3& principal, const MohrCoulombConstants& c);

/// The Itasca return: choose shear or tension by comparing the distances
/// F_s/√(1+N_φ²) and f_t = σ3 − σ_t (the larger violation wins, §4 "Choosing
/// shear or tension"), correct, then apply the apex correction.
[[nodiscard]] PrincipalReturn mohr_coulomb_return(const Vec3& principal_trial, const MohrCoulombConstants& c);

}  // namespace dfc::constitutive
