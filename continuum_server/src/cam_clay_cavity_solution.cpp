#include "dfc/continuum/cam_clay_cavity_solution.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace dfc::continuum {

namespace {

bool is_spherical(const CamClayCavity& c) { return c.geometry == CavityGeometry::spherical; }

// Isochoric kinematics in d = 2 (cylinder, plane strain) or 3 (sphere)
// dimensions: r^d − r₀^d = a^d − a₀^d, so a point's hoop strain ε = ln(r/r₀)
// fixes its strains: (ε_r, ε_θ, ε_z) = (−ε, ε, 0) or (−2ε, ε, ε), and the
// deviatoric strain ε_q = √(2/3)‖e‖ = k_q ε with k_q = 2/√3 or 2.
double dimension(const CamClayCavity& c) { return is_spherical(c) ? 3.0 : 2.0; }
double deviatoric_strain_per_hoop_strain(const CamClayCavity& c) { return is_spherical(c) ? 2.0 : 2.0 / std::sqrt(3.0); }
// From an isotropic start the stress deviator stays parallel to the strain
// deviator's direction, so σ_r − σ_θ = k_σ q with k_σ = 2/√3 (cylinder: the
// deviator (s, −s, 0), q = √3 s) or 1 (sphere: (2q/3, −q/3, −q/3)); the
// radial equilibrium dσ_r/dr + m (σ_r − σ_θ)/r = 0 (m = 1 cylinder, 2 sphere)
// then weighs q with k = m k_σ.
double equilibrium_weight(const CamClayCavity& c) { return is_spherical(c) ? 2.0 : 2.0 / std::sqrt(3.0); }
// σ_r − p over q: 1/√3 (cylinder, σ_z = p), 2/3 (sphere).
double radial_deviator_per_q(const CamClayCavity& c) { return is_spherical(c) ? 2.0 / 3.0 : 1.0 / std::sqrt(3.0); }

// The ring r … r + dr has hoop strain ε(r) with dr/r = −dε/(e^{dε} − 1)
// (differentiate e^{−dε} = 1 − (a^d − a₀^d)/r^d), so
//   p(a) = σ₀ + ∫_{ε_b}^{ε_a} k q(ε) dε/(e^{dε} − 1),
// in large strain, as in the undrained analyses of Collins & Yu (1996) and
// Cao, Teh & Chang (2001); exact for a finite body whose outer radius b
// carries σ₀ (ε_b its hoop strain). The integrand is
// finite at ε → 0 (q ≈ 3G k_q ε, elastic).
double hoop_strain(const CamClayCavity& c, double point_initial_radius, double cavity_radius) {
  const double d = dimension(c);
  const double swept = std::pow(cavity_radius, d) - std::pow(c.initial_radius, d);
  return std::log1p(swept / std::pow(point_initial_radius, d)) / d;
}

// The path integrated in ε: the plastic volumetric strain e (p′ = p₀′ − K e
// at constant volume, p_c = p_c0 exp(ρ e)), q, and the cavity integral F(ε) =
// ∫₀^ε k q/(e^{dε} − 1) dε, so that p(a) = σ₀ + F(ε_a) − F(ε_b).
struct PathPoint {
  double strain = 0.0;  ///< ε
  double e = 0.0;
  double q = 0.0;
  double integral = 0.0;
  bool yielded = false;
};

struct PathRates {
  double e = 0.0;
  double q = 0.0;
  double integral = 0.0;
};

class UndrainedPath {
 public:
  explicit UndrainedPath(const CamClayCavity& c)
      : c_(c),
        kq_(deviatoric_strain_per_hoop_strain(c)),
        d_(dimension(c)),
        yield_q_(c.critical_state_ratio *
                 std::sqrt(c.in_situ_effective_pressure * (c.preconsolidation_pressure - c.in_situ_effective_pressure))),
        yield_strain_(yield_q_ / (3.0 * c.shear_modulus * kq_)) {
    assert(c.preconsolidation_pressure >= c.in_situ_effective_pressure && "the in-situ state lies inside the yield surface");
    // Fixed RK4 steps, small against the path's fastest rate: the Jacobian of
    // the rates below is at most about k_q (3G + K)/p′, p′ ≥ min(p₀′, p_c0/2)
    // on the way to the critical state; 0.02 of its inverse. Measured
    // (tests/continuum/cam_clay_cavity_solution_test.cpp): the path is the
    // shared model's to 1e-5 of p₀′ (the model's own stepping), the integral's
    // tail at the critical state its closed form to 1e-9.
    const double smallest_p = std::min(c.in_situ_effective_pressure, 0.5 * c.preconsolidation_pressure);
    step_ = std::min(1e-3, 0.02 * smallest_p / (kq_ * (3.0 * c.shear_modulus + c.bulk_modulus)));
  }

  [[nodiscard]] PathPoint start() const { return {0.0, 0.0, 0.0, 0.0, yield_q_ <= 0.0}; }

  /// The path from `from` to hoop strain `to` ≥ from.strain.
  [[nodiscard]] PathPoint advance(PathPoint from, double to) const {
    if (!from.yielded && to > yield_strain_) {
      // Elastic up to first yield (q = 3G ε_q at p′ = p₀′), then plastic:
      // the step lands on the kink so that RK4 never steps across it.
      from = integrate(from, yield_strain_);
      from.q = yield_q_;
      from.yielded = true;
    }
    return integrate(from, to);
  }

  [[nodiscard]] CamClayPathState state(const PathPoint& point) const {
    return {c_.in_situ_effective_pressure - c_.bulk_modulus * point.e, point.q,
            c_.preconsolidation_pressure * std::exp(c_.hardening_rate * point.e), point.e};
  }

 private:
  [[nodiscard]] PathPoint integrate(PathPoint from, double to) const {
    if (to <= from.strain) return from;
    const double n = std::ceil((to - from.strain) / step_);
    const double h = (to - from.strain) / n;
    const bool yielded = from.yielded;
    const auto shifted = [&](const PathPoint& p, const PathRates& r, double by) {
      return PathPoint{p.strain + by, p.e + by * r.e, p.q + by * r.q, p.integral + by * r.integral, yielded};
    };
    PathPoint p = from;
    for (long i = 0; i < static_cast<long>(n); ++i) {
      const PathRates r1 = rates(p);
      const PathRates r2 = rates(shifted(p, r1, 0.5 * h));
      const PathRates r3 = rates(shifted(p, r2, 0.5 * h));
      const PathRates r4 = rates(shifted(p, r3, h));
      p.e += h / 6.0 * (r1.e + 2.0 * r2.e + 2.0 * r3.e + r4.e);
      p.q += h / 6.0 * (r1.q + 2.0 * r2.q + 2.0 * r3.q + r4.q);
      p.integral += h / 6.0 * (r1.integral + 2.0 * r2.integral + 2.0 * r3.integral + r4.integral);
      p.strain = from.strain + double(i + 1) * h;
    }
    p.strain = to;
    return p;
  }

  // Rates per unit hoop strain. Elastic: dq = 3G dε_q. Plastic, on the
  // yield surface f = q²/M² + p′(p′ − p_c) = 0 with associated flow
  // (dε_q^p = de f_q/f_p, f_q = 2q/M², f_p = 2p′ − p_c), constant volume
  // (dp′ = −K de), dq = 3G(dε_q − dε_q^p) and dp_c = ρ p_c de; the
  // consistency condition f_q dq + f_p dp′ − p′ dp_c = 0 gives
  //   de = 3G f_q f_p dε_q / D,  dq = 3G (K f_p² + ρ p′ p_c f_p) dε_q / D,
  //   D = 3G f_q² + K f_p² + ρ p′ p_c f_p,
  // regular at the isotropic start (f_q = 0: dq = 3G dε_q) and at the
  // critical state (f_p = 0: de = dq = 0), so neither end needs special care.
  [[nodiscard]] PathRates rates(const PathPoint& p) const {
    const double three_g = 3.0 * c_.shear_modulus;
    PathRates r;
    r.integral = p.strain > 0.0 ? equilibrium_weight(c_) * p.q / std::expm1(d_ * p.strain)
                                : equilibrium_weight(c_) * three_g * kq_ / d_;  // the limit ε → 0
    if (!p.yielded) {
      r.q = three_g * kq_;
      return r;
    }
    const CamClayPathState s = state(p);
    const double m2 = c_.critical_state_ratio * c_.critical_state_ratio;
    const double fq = 2.0 * p.q / m2;
    const double fp = 2.0 * s.mean_effective_stress - s.preconsolidation_pressure;
    const double hardening = c_.hardening_rate * s.mean_effective_stress * s.preconsolidation_pressure * fp;
    const double denominator = three_g * fq * fq + c_.bulk_modulus * fp * fp + hardening;
    assert(denominator > 0.0 && "the undrained path softens faster than it can be strain-controlled");
    r.e = kq_ * three_g * fq * fp / denominator;
    r.q = kq_ * three_g * (c_.bulk_modulus * fp * fp + hardening) / denominator;
    return r;
  }

  const CamClayCavity& c_;
  double kq_;
  double d_;
  double yield_q_;
  double yield_strain_;
  double step_ = 0.0;
};

// Total radial stress at the current radius r when the cavity radius is a:
// σ₀ + F(ε(r)) − F(ε_b), and the path's state at r.
struct RadialStress {
  double total = 0.0;
  CamClayPathState state;
};

RadialStress radial_stress(const CamClayCavity& cavity, double cavity_radius, double radius) {
  const UndrainedPath path(cavity);
  const PathPoint outer = path.advance(path.start(), hoop_strain(cavity, cavity.outer_radius, cavity_radius));
  assert(radius >= cavity_radius && "the point lies in the soil");
  // r₀ of the point now at r: r₀^d = r^d − (a^d − a₀^d).
  const double d = dimension(cavity);
  const double initial = std::pow(std::pow(radius, d) - (std::pow(cavity_radius, d) - std::pow(cavity.initial_radius, d)), 1.0 / d);
  const PathPoint here = path.advance(outer, hoop_strain(cavity, initial, cavity_radius));
  return {cavity.in_situ_effective_pressure + cavity.in_situ_pore_pressure + here.integral - outer.integral, path.state(here)};
}

}  // namespace

CamClayPathState undrained_path_state(const CamClayCavity& cavity, double strain) {
  const UndrainedPath path(cavity);
  return path.state(path.advance(path.start(), strain));
}

double cavity_pressure(const CamClayCavity& cavity, double cavity_radius) {
  return radial_stress(cavity, cavity_radius, cavity_radius).total;
}

double excess_pore_pressure(const CamClayCavity& cavity, double cavity_radius, double radius) {
  const RadialStress s = radial_stress(cavity, cavity_radius, radius);
  const double total_mean = s.total - radial_deviator_per_q(cavity) * s.state.deviatoric_stress;
  return total_mean - s.state.mean_effective_stress - cavity.in_situ_pore_pressure;
}

double limit_pressure(const CamClayCavity& cavity) {
  // F(∞): the integral until the path has reached the critical state (q
  // unchanged to round-off over a stretch of 0.05 in ε: the approach is
  // exponential), then the tail with that q in closed form,
  // ∫_E^∞ k q dε/(e^{dε} − 1) = −(k q/d) ln(1 − e^{−dE}).
  const UndrainedPath path(cavity);
  const double d = dimension(cavity);
  constexpr double kStretch = 0.05;
  PathPoint far = path.advance(path.start(), kStretch);
  while (far.strain < 20.0 / d) {  // beyond, the tail is 1e-9 of the whole whatever q does
    const PathPoint next = path.advance(far, far.strain + kStretch);
    const bool settled = next.yielded && std::abs(next.q - far.q) <= 1e-13 * next.q;
    far = next;
    if (settled) break;
  }
  const double tail = -equilibrium_weight(cavity) * far.q / d * std::log(-std::expm1(-d * far.strain));
  return cavity.in_situ_effective_pressure + cavity.in_situ_pore_pressure + far.integral + tail;
}

}  // namespace dfc::continuum
