// The semi-analytical reference of the undrained Cam clay cavity
// (dfc/continuum/cam_clay_cavity_solution.hpp; docs/continuum_pile.md §7.1),
// checked on its own: its material path against the shared model driven at
// one point, and its cavity integral against the Tresca closed form where the
// two must agree (a start on the critical state, OCR = 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/constitutive/material_point_driver.hpp"
#include "dfc/constitutive/structured_cam_clay_model.hpp"
#include "dfc/continuum/cam_clay_cavity_solution.hpp"
#include "dfc/continuum/tresca_cavity_closed_form.hpp"

namespace dfc::continuum {
namespace {

// A soft clay: p₀′ = 200 kPa, M = 1.2, ρ = v/(λ − κ) = 2/0.16 = 12.5.
constexpr double kInSitu = 200e3;
constexpr double kSlope = 1.2;
constexpr double kHardening = 12.5;

CamClayCavity cavity(CavityGeometry geometry, double young_modulus, double overconsolidation, double outer_radius) {
  const constitutive::ElasticModuli moduli = constitutive::moduli_from_young_poisson(young_modulus, 0.3);
  return {geometry, moduli.shear, moduli.bulk, kSlope, kHardening, kInSitu, overconsolidation * kInSitu, 0.0, 1.0, outer_radius};
}

// OCR = 2 puts p₀′ at the top of the ellipse: the undrained path rises
// elastically to q = M p₀′ and stays there (the critical state, no volume
// change), so the material is Tresca with s_u = (σ_r − σ_θ)/2 = M p₀′/√3
// (cylinder, q = √3 s_u) or M p₀′/2 (sphere, q = 2 s_u), incompressible. The
// Tresca closed form (§7) takes its elastic zone in small strain, the
// reference in logarithmic strain: the strain to first yield, s_u/(2G)
// (cylinder), enters the elastic zone's stress and the plastic radius at
// second order, terms of order s_u²/G in the pressure (expanding
// ∫ 3G k_q k ε/(e^{dε} − 1) dε to first yield gives s_u²/(4G) for the
// cylinder's elastic zone). Tolerance s_u²/G (250 Pa, 190 Pa; measured at
// most 0.6 of it, at a/a₀ = 10): an error of order s_u (a wrong weight,
// strain or bound of the integral) is a thousand times that.
TEST(CamClayCavitySolution, StartingOnTheCriticalStateItIsTheIncompressibleTrescaClosedForm) {
  for (const CavityGeometry geometry : {CavityGeometry::cylindrical, CavityGeometry::spherical}) {
    const bool sphere = geometry == CavityGeometry::spherical;
    // b such that the plastic zone (c ≈ a √(G/s_u), a ∛(G/s_u)) stays
    // inside it up to a/a₀ = 10, where the Tresca closed form holds, and
    // reaches towards it (c/b ≈ 0.8), so that its c²/b², c³/b³ terms count.
    const double outer = sphere ? 100.0 : 300.0;
    const CamClayCavity clay = cavity(geometry, 200e6, 2.0, outer);
    const double strength = kSlope * kInSitu / (sphere ? 2.0 : std::sqrt(3.0));
    const TrescaCavity tresca{geometry, clay.shear_modulus, 1e6 * clay.shear_modulus, strength, kInSitu, 1.0, outer};
    const double tolerance = strength * strength / clay.shear_modulus;
    for (const double ratio : {1.5, 3.0, 10.0}) {
      const double expected = cavity_pressure(tresca, ratio);
      const double pressure = cavity_pressure(clay, ratio);
      std::printf("%s a/a0 = %4.1f: p = %.2f kPa, Tresca %.2f kPa (s_u = %.1f kPa, G/s_u = %.0f)\n", sphere ? "sphere" : "cylinder",
                  ratio, pressure / 1e3, expected / 1e3, strength / 1e3, clay.shear_modulus / strength);
      EXPECT_NEAR(pressure, expected, tolerance) << "a/a0 = " << ratio;
      // No volume change at the critical state: p′ stays p₀′, and the wall's
      // total mean stress is σ_r − s_u (cylinder, σ_z the mean) or
      // σ_r − 4s_u/3 (sphere).
      const double total_mean = expected - (sphere ? 4.0 / 3.0 : 1.0) * strength;
      EXPECT_NEAR(excess_pore_pressure(clay, ratio, ratio), total_mean - kInSitu, tolerance) << "a/a0 = " << ratio;
    }
  }
}

// The same start, an infinite medium: Yu & Houlsby's (1991) limit for
// φ = ψ = 0, σ₀ + s_u [1 + ln(G/s_u)] (sphere 4/3 of the bracket), which
// the reference exceeds by s_u²/(4G) (cylinder; plastic zone −s_u ln(1 −
// e^{−s_u/G}) = s_u ln(G/s_u) + s_u²/(2G), elastic zone s_u − s_u²/(4G)).
// And the pressure at a/a₀ = 100 falls short of the limit by what the ring
// beyond ε_a = ln(a/a₀) would add at the critical state, −(k q/d)
// ln(1 − (a₀/a)^d) (k q = 2s_u, d = 2; k q = 4s_u, d = 3), to 1e-8 (the
// quadrature's error, measured 1e-9).
TEST(CamClayCavitySolution, LimitPressureAtTheCriticalStateIsYuAndHoulsbys) {
  for (const CavityGeometry geometry : {CavityGeometry::cylindrical, CavityGeometry::spherical}) {
    const bool sphere = geometry == CavityGeometry::spherical;
    const double infinite = std::numeric_limits<double>::infinity();
    const CamClayCavity clay = cavity(geometry, 200e6, 2.0, infinite);
    const double strength = kSlope * kInSitu / (sphere ? 2.0 : std::sqrt(3.0));
    const TrescaCavity tresca{geometry, clay.shear_modulus, 1e6 * clay.shear_modulus, strength, kInSitu, 1.0, infinite};
    const double limit = limit_pressure(clay);
    const double ratio = 100.0;
    const double d = sphere ? 3.0 : 2.0;
    const double beyond = -(sphere ? 4.0 : 2.0) * strength / d * std::log1p(-std::pow(ratio, -d));
    std::printf("%s: limit %.3f kPa, Yu & Houlsby %.3f kPa, p(100 a0) %.3f kPa + %.3f kPa\n", sphere ? "sphere" : "cylinder",
                limit / 1e3, limit_pressure(tresca) / 1e3, cavity_pressure(clay, ratio) / 1e3, beyond / 1e3);
    EXPECT_NEAR(limit, limit_pressure(tresca), strength * strength / clay.shear_modulus);
    EXPECT_NEAR(cavity_pressure(clay, ratio) + beyond, limit, 1e-8 * limit);
  }
}

// The material path: the shared model (structured Cam clay with p_t = 0,
// ξ_s = 0, M_f = M_g: Modified Cam clay with linear elasticity) driven at one
// point through the cylinder's isochoric plane strain, (Δε_r, Δε_θ, Δε_z) =
// (−δ, δ, 0), sums to the hoop strain ε (logarithmic for fixed axes), normally
// consolidated and at OCR 1.5. The model's backward-Euler return is first
// order in δ: δ = 1e-6 while the path turns (ε ≤ 0.02), then 1e-4 on the
// critical state, where the state no longer changes. Tolerance 1e-4 of p₀′
// (20 Pa): what that stepping leaves (measured at most 1.7 Pa), and more
// than three orders below the path's own changes (p′ falls by 90 kPa, q
// rises to 134 kPa).
TEST(CamClayCavitySolution, MaterialPathIsTheSharedModelsAtConstantVolume) {
  for (const double overconsolidation : {1.0, 1.5}) {
    const CamClayCavity clay = cavity(CavityGeometry::cylindrical, 12e6, overconsolidation, 100.0);
    constitutive::StructuredCamClayParameters parameters;
    parameters.moduli = constitutive::moduli_from_young_poisson(12e6, 0.3);
    parameters.ps0 = clay.preconsolidation_pressure;
    parameters.mf = kSlope;
    parameters.mg = kSlope;
    parameters.rho_s = kHardening;
    const constitutive::StructuredCamClayModel model(parameters);
    constitutive::MaterialPointDriver point(model, constitutive::Stress::isotropic(-kInSitu));
    double strain = 0.0;
    for (const double checkpoint : {0.001, 0.003, 0.01, 0.02, 0.5}) {
      const double increment = checkpoint <= 0.02 ? 1e-6 : 1e-4;
      const long steps = std::lround((checkpoint - strain) / increment);
      for (long s = 0; s < steps; ++s) point.strain_step(constitutive::SymTensor{-increment, increment, 0.0, 0.0, 0.0, 0.0});
      strain = checkpoint;
      const CamClayPathState reference = undrained_path_state(clay, checkpoint);
      const double ps = point.state()[constitutive::StructuredCamClayModel::kPs];
      std::printf("OCR %.1f, eps = %.3f: p' %.3f / %.3f kPa, q %.3f / %.3f kPa, p_c %.3f / %.3f kPa (model / reference)\n",
                  overconsolidation, checkpoint, point.mean_pressure() / 1e3, reference.mean_effective_stress / 1e3,
                  point.deviatoric_stress() / 1e3, reference.deviatoric_stress / 1e3, ps / 1e3, reference.preconsolidation_pressure / 1e3);
      const double tolerance = 1e-4 * kInSitu;
      EXPECT_NEAR(point.mean_pressure(), reference.mean_effective_stress, tolerance) << "OCR " << overconsolidation << ", eps " << checkpoint;
      EXPECT_NEAR(point.deviatoric_stress(), reference.deviatoric_stress, tolerance) << "OCR " << overconsolidation << ", eps " << checkpoint;
      EXPECT_NEAR(ps, reference.preconsolidation_pressure, tolerance) << "OCR " << overconsolidation << ", eps " << checkpoint;
    }
    // At ε = 0.5 the path is on the critical state line: q = M p′, p′ = p_c/2.
    const CamClayPathState end = undrained_path_state(clay, 0.5);
    EXPECT_NEAR(end.deviatoric_stress, kSlope * end.mean_effective_stress, 1e-9 * kInSitu);
    EXPECT_NEAR(end.preconsolidation_pressure, 2.0 * end.mean_effective_stress, 1e-9 * kInSitu);
  }
}

}  // namespace
}  // namespace dfc::continuum
