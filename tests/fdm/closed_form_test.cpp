// The closed forms of the verification suite (docs/theory/fdm.md §2) against the
// reference values quoted there and against their own limiting cases, so that
// a table row can only pass against a correct formula.
#include <gtest/gtest.h>

#include <cmath>

#include "dfc/fdm/verification/boussinesq_disc.hpp"
#include "dfc/fdm/verification/kirsch_hole.hpp"
#include "dfc/fdm/verification/lame_cylinder.hpp"
#include "dfc/fdm/verification/salencon_hole.hpp"
#include "dfc/fdm/verification/spherical_cavity.hpp"

namespace dfc::fdm::verification {
namespace {

TEST(ClosedForms, SalenconMatchesTheItascaReferenceValues) {
  // §2(f): R0 = 1.735 m, σ_re = 12.01 MPa, u_r(a) = −12.17 mm (ψ = 0°) and
  // −28.10 mm (ψ = 30°), u_r(R0) = −5.573 mm; the values are quoted to 4 digits.
  SalenconSolution s;
  EXPECT_NEAR(s.plastic_radius(), 1.735, 5e-4);
  EXPECT_NEAR(s.interface_stress() / 1e6, 12.01, 5e-3);
  EXPECT_NEAR(s.radial_displacement(1.0) * 1e3, -12.17, 5e-3);
  EXPECT_NEAR(s.radial_displacement(s.plastic_radius()) * 1e3, -5.573, 5e-4);
  s.dilation_deg = 30.0;
  EXPECT_NEAR(s.radial_displacement(1.0) * 1e3, -28.10, 5e-3);
  // Continuity of the stresses at R0 and the free wall.
  const double r0 = s.plastic_radius();
  EXPECT_NEAR(s.radial_stress(r0 * (1 - 1e-12)), s.radial_stress(r0), 1e-3);
  EXPECT_NEAR(s.hoop_stress(r0 * (1 - 1e-12)), s.hoop_stress(r0), 1e-3);
  EXPECT_NEAR(s.radial_stress(1.0), 0.0, 1e-6);
}

TEST(ClosedForms, KirschWallHoopStressIsThreeP1MinusP2AndFarFieldIsRecovered) {
  const KirschSolution k;
  EXPECT_NEAR(k.hoop_stress(1.0, std::numbers::pi / 2), 3 * k.p1 - k.p2, 1e-6);
  EXPECT_NEAR(k.hoop_stress(1.0, 0.0), 3 * k.p2 - k.p1, 1e-6);
  EXPECT_NEAR(k.radial_stress(1.0, 0.3), 0.0, 1e-6);
  EXPECT_NEAR(k.shear_stress(1.0, 0.3), 0.0, 1e-6);
  EXPECT_NEAR(k.radial_stress(1e4, 0.0), k.p1, 1e-7 * k.p1);  // θ = 0 is the p1 direction; a²/r² = 1e-8
  // Isotropic far field: the classical convergence p a/(2G).
  KirschSolution iso;
  iso.p2 = iso.p1;
  EXPECT_NEAR(iso.radial_displacement_towards_hole(1.0, 0.7), iso.p1 / (2 * iso.shear_modulus), 1e-15);
}

TEST(ClosedForms, LameMeetsItsBoundaryConditions) {
  const LameSolution l;
  EXPECT_NEAR(l.radial_stress(l.inner_radius), -l.inner_pressure, 1e-6);
  EXPECT_NEAR(l.radial_stress(l.outer_radius), -l.outer_pressure, 1e-6);
  // Outer wall held: loaded inside, no radial displacement outside (1e-6 Pa
  // and 1e-18 m are round-off of 1e7 Pa and of a ~1e-3 m displacement).
  LameSolution held;
  held.outer_wall_held = true;
  EXPECT_NEAR(held.radial_stress(held.inner_radius), -held.inner_pressure, 1e-6);
  EXPECT_NEAR(held.radial_displacement(held.outer_radius), 0.0, 1e-18);
  EXPECT_GT(held.radial_displacement(held.inner_radius), 0.0);  // pushed outwards
}

TEST(ClosedForms, BoussinesqSurfaceSettlementAndStressLimits) {
  const BoussinesqSolution b;
  EXPECT_NEAR(b.axis_settlement(0.0), 2 * b.pressure * b.radius * (1 - b.poisson_ratio * b.poisson_ratio) / b.young_modulus, 1e-15);
  EXPECT_NEAR(b.axis_vertical_stress(0.0), b.pressure, 1e-9);
  // Far below, the disc acts as a point load: σ_z → 3P/(2π z²), u_z → P(3 − 2ν)/(4πG z).
  const double z = 100.0 * b.radius;
  const double force = b.pressure * std::numbers::pi * b.radius * b.radius;
  EXPECT_NEAR(b.axis_vertical_stress(z), 3 * force / (2 * std::numbers::pi * z * z), 1e-3 * b.axis_vertical_stress(z));
  EXPECT_NEAR(b.axis_settlement(z), b.point_load_displacement(0.0, z).y(), 1e-3 * b.axis_settlement(z));
}

TEST(ClosedForms, SphericalCavityFirstYieldPutsTheWallOnTheMohrCoulombSurface) {
  const SphericalCavitySolution s;
  const double p = s.first_yield_pressure();
  const double y = 2 * s.cohesion * std::sqrt(s.kp());
  EXPECT_NEAR(s.radial_stress(1.0, p), s.kp() * s.hoop_stress(1.0, p) + y, 1e-6);
  EXPECT_NEAR(s.radial_stress(1.0, p), p, 1e-9);
}

}  // namespace
}  // namespace dfc::fdm::verification
