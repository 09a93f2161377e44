// Kinematics of the axisymmetric triangle (docs/continuum_pile.md §2–§3).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dfc/continuum/triangle_kinematics.hpp"

namespace dfc::continuum {
namespace {

const NodalVectors kTriangle{Point(1.0, 0.0), Point(2.0, 0.5), Point(1.2, 1.0)};
// Exact algebra on O(1) numbers: round-off only.
constexpr double kRoundOff = 1e-12;

TEST(TriangleKinematics, AffineVelocityGivesItsGradientAndTheHoopRateAtTheCentroid) {
  const TriangleGeometry g = triangle_geometry(kTriangle);
  NodalVectors v;
  for (int i = 0; i < 3; ++i) v[i] = Point(0.3 * kTriangle[i].x() + 0.2 * kTriangle[i].y(), -0.1 * kTriangle[i].x() + 0.4 * kTriangle[i].y());
  const VelocityGradient l = velocity_gradient(g, v);
  EXPECT_NEAR(l.rr, 0.3, kRoundOff);
  EXPECT_NEAR(l.rz, 0.2, kRoundOff);
  EXPECT_NEAR(l.zr, -0.1, kRoundOff);
  EXPECT_NEAR(l.zz, 0.4, kRoundOff);
  const double r = g.centroid_r;
  const double z = (kTriangle[0].y() + kTriangle[1].y() + kTriangle[2].y()) / 3.0;
  EXPECT_NEAR(l.hoop, (0.3 * r + 0.2 * z) / r, kRoundOff);
  EXPECT_NEAR(spin_rz(l), 0.5 * (0.2 + 0.1), kRoundOff);
}

TEST(TriangleKinematics, RigidRotationInTheMeridianPlaneDoesNotStrainAndRotatesTheStress) {
  // A rigid rotation of the meridian section changes r, hence the hoop rate;
  // the in-plane part of D must vanish and the spin must be the rotation rate.
  const TriangleGeometry g = triangle_geometry(kTriangle);
  NodalVectors v;
  const double rate = 1e-3;
  for (int i = 0; i < 3; ++i) v[i] = Point(rate * kTriangle[i].y(), -rate * kTriangle[i].x());
  const VelocityGradient l = velocity_gradient(g, v);
  const SymTensor d = rate_of_deformation(l);
  EXPECT_NEAR(d.xx, 0.0, kRoundOff);
  EXPECT_NEAR(d.zz, 0.0, kRoundOff);
  EXPECT_NEAR(d.zx, 0.0, kRoundOff);
  EXPECT_NEAR(spin_rz(l), rate, kRoundOff);
  // Jaumann: σ_rr = −100 alone gains (Ωσ − σΩ)_rz = −Ω_rz σ_rr = 100 ω and keeps its trace.
  Stress s;
  s.xx = -100.0;
  rotate_by_jaumann(s, rate);
  EXPECT_NEAR(s.zx, 100.0 * rate, kRoundOff);
  EXPECT_NEAR(s.trace(), -100.0, kRoundOff);
}

TEST(TriangleKinematics, UniformStressForcesSumToTheHoopTerm) {
  // A uniform isotropic stress −p: with Σ_i ∂N_i/∂r = Σ_i ∂N_i/∂z = 0 and
  // Σ_i N_i = 1 only the hoop term survives in the sum over the nodes:
  // Σ f_r = V σ_θθ / r̄ = −p 2π A, Σ f_z = 0.
  const TriangleGeometry g = triangle_geometry(kTriangle);
  const double p = 1e5;
  const NodalVectors f = internal_forces(g, Stress::isotropic(-p));
  const double sum_r = f[0].x() + f[1].x() + f[2].x();
  const double sum_z = f[0].y() + f[1].y() + f[2].y();
  EXPECT_NEAR(sum_r, -p * 2.0 * std::numbers::pi * g.area, 1e-9 * p);
  EXPECT_NEAR(sum_z, 0.0, 1e-9 * p);
}

TEST(TriangleKinematics, SmallestAngleOfARightIsoscelesTriangleIs45Degrees) {
  EXPECT_NEAR(smallest_angle_deg({Point(1, 0), Point(2, 0), Point(1, 1)}), 45.0, 1e-12);
  EXPECT_NEAR(smallest_angle_deg({Point(1, 0), Point(2, 0), Point(1.5, 0.5 * std::sqrt(3.0))}), 60.0, 1e-12);
}

TEST(TriangleKinematics, StiffnessRowSumsArePositiveAndScaleWithTheModulus) {
  const TriangleGeometry g = triangle_geometry(kTriangle);
  const auto soft = stiffness_row_sums(g, 1e6, 5e5);
  const auto stiff = stiffness_row_sums(g, 2e6, 1e6);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(soft[i], 0.0);
    EXPECT_NEAR(stiff[i], 2.0 * soft[i], 1e-9 * stiff[i]);
  }
}

}  // namespace
}  // namespace dfc::continuum
