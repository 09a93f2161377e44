#include "dfc/constitutive/mohr_coulomb_return.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace dfc::constitutive {

namespace {

double flow_number(double angle_deg) {
  const double s = std::sin(angle_deg * std::numbers::pi / 180.0);
  return (1.0 + s) / (1.0 - s);
}

// §4 "Tension correction" (Itasca `tensionCorrection`): one, two or three
// principal stresses above σ_t are set to it; the others take the elastic
// coupling α2 of the associated return.
Vec3 tension_correction(Vec3 s, const MohrCoulombConstants& c) {
  const double ftz = s.z() - c.tension;
  const double fty = s.y() - c.tension;
  if (s.x() - c.tension > 0.0) return Vec3::Constant(c.tension);  // triaxial tension
  if (fty > 0.0) {
    s.x() -= (fty + ftz) * c.alpha2 / (c.alpha1 + c.alpha2);
    s.y() = c.tension;
    s.z() = c.tension;
    return s;
  }
  const double coupling = ftz * c.alpha2 / c.alpha1;  // single surface, λ_t = f_t/α1
  s.x() -= coupling;
  s.y() -= coupling;
  s.z() = c.tension;
  return s;
}

}  // namespace

MohrCoulombConstants MohrCoulombConstants::from(const MohrCoulombStrength& strength, const ElasticModuli& moduli) {
  MohrCoulombConstants c;
  c.n_phi = flow_number(strength.friction_angle_deg);
  c.n_psi = flow_number(strength.dilation_angle_deg);
  c.two_c_sqrt_n_phi = 2.0 * strength.cohesion * std::sqrt(c.n_phi);
  c.distance_scale = std::sqrt(1.0 + c.n_phi * c.n_phi);
  c.apex = strength.friction_angle_deg > 0.0 ? strength.cohesion / std::tan(strength.friction_angle_deg * std::numbers::pi / 180.0)
                                             : std::numeric_limits<double>::infinity();
  // Itasca `updateParameters`: σ_t <= c/tanφ; no tensile strength without cohesion and friction.
  c.tension = std::min(strength.tensile_strength, c.apex);
  if (strength.friction_angle_deg == 0.0 && strength.cohesion == 0.0) c.tension = 0.0;
  c.alpha1 = moduli.bulk + 4.0 * moduli.shear / 3.0;
  c.alpha2 = moduli.bulk - 2.0 * moduli.shear / 3.0;
  // §4 "Shear correction": r_d = (α1 − N_ψ α2) − (α2 − N_ψ α1) N_φ.
  const double ra = c.alpha1 - c.n_psi * c.alpha2;
  const double rb = c.alpha2 - c.n_psi * c.alpha1;
  const double rd = ra - rb * c.n_phi;
  c.shear_factors = Vec3(ra / rd, c.alpha2 * (1.0 - c.n_psi) / rd, rb / rd);
  return c;
}

double mohr_coulomb_shear_function(const Vec3& principal, const MohrCoulombConstants& c) {
  return c.n_phi * principal.z() - principal.x() - c.two_c_sqrt_n_phi;
}

PrincipalReturn mohr_coulomb_return(const Vec3& principal_trial, const MohrCoulombConstants& c) {
  PrincipalReturn out{principal_trial, MohrCoulombFailure::none};
  const double fs = mohr_coulomb_shear_function(principal_trial, c);
  const double fs_distance = fs / c.distance_scale;
  const double ft = principal_trial.z() - c.tension;
  if (fs_distance > 0.0 && fs_distance >= ft) {
    out.stress += fs * c.shear_factors;  // brings F_s to zero exactly
    out.failure = MohrCoulombFailure::shear;
  } else if (ft > 0.0 && ft >= fs_distance) {
    out.stress = tension_correction(principal_trial, c);
    out.failure = MohrCoulombFailure::tension;
  }
  // Apex correction (Itasca `apexCorrection`): a shear return past the apex
  // lands in tension beyond c/tanφ; the only admissible point there is the apex.
  if (out.stress.maxCoeff() >= c.apex) {
    out.stress = Vec3::Constant(c.apex);
    out.failure = MohrCoulombFailure::tension;
  }
  return out;
}

}  // namespace dfc::constitutive
