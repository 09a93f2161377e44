// The `linear` law as a pure function (reference/dem-physics.md §2.3) and its registry entry.
#include <cmath>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/common/errors.hpp"

namespace dfc::dem {
namespace {

ContactKinematics pressed(double overlap, Vec3 relative_velocity = {}, double dt = 1e-4) {
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = overlap;
  k.relative_velocity = relative_velocity;
  k.effective_mass = 1e-3;
  k.radius_first = k.radius_second = 1e-3;
  k.dt = dt;
  return k;
}

LinearLaw law(double kn, double ks, double mu, double beta = 0.0) { return {.kn = kn, .ks = ks, .friction = mu, .damping_ratio_normal = beta}; }

TEST(LinearLaw, NormalForceIsStiffnessTimesOverlapPushingTheFirstBodyAway) {
  double history[3] = {0, 0, 0};
  const ContactForce f = law(1e5, 1e5, 0.5).evaluate(pressed(2e-5), history);
  // F_n = k_n * overlap along -n on the first body; one product, so exact.
  EXPECT_EQ(f.on_first.z, -1e5 * 2e-5);
  EXPECT_EQ(f.on_first.x, 0.0);
  EXPECT_EQ(f.on_first.y, 0.0);
}

TEST(LinearLaw, ShearForceGrowsByKsTimesSlipIncrementThenCapsAtCoulombLimit) {
  const LinearLaw l = law(1e5, 5e4, 0.3);
  double h[3] = {0, 0, 0};
  const ContactKinematics sliding = pressed(1e-5, {0.01, 0.0, 0.0});  // F_n = 1 N, cap mu F_n = 0.3 N
  // dF_s = k_s v_t dt = 5e4 * 0.01 * 1e-4 = 0.05 N per step (incremental law).
  for (int s = 0; s < 3; ++s) (void)l.evaluate(sliding, h);
  EXPECT_NEAR(h[0], 0.15, 1e-15);
  ContactForce f{};
  for (int s = 0; s < 20; ++s) f = l.evaluate(sliding, h);
  // |F_s| = mu F_n exactly at the cap (one scaling; 1e-15 covers its rounding).
  EXPECT_NEAR(std::hypot(f.on_first.x, f.on_first.y), 0.3 * 1.0, 1e-15);
  EXPECT_GT(f.on_first.x, 0.0);  // the second body moving +x drags the first along +x
  // Reversing the slip unloads the spring elastically from the cap: 0.3 - 0.05.
  f = l.evaluate(pressed(1e-5, {-0.01, 0.0, 0.0}), h);
  EXPECT_NEAR(f.on_first.x, 0.25, 1e-15);
}

TEST(LinearLaw, ShearForceRotatesWithTheContactPlaneKeepingItsMagnitude) {
  double h[3] = {0.2, 0.0, 0.0};
  ContactKinematics k = pressed(1e-5);
  const double a = 0.1;  // the contact normal has turned by 0.1 rad about y
  k.normal = {std::sin(a), 0.0, std::cos(a)};
  (void)law(1e5, 1e5, 10.0).evaluate(k, h);
  const Vec3 shear{h[0], h[1], h[2]};
  EXPECT_NEAR(dot(shear, k.normal), 0.0, 1e-16);
  EXPECT_NEAR(norm(shear), 0.2, 1e-16);
}

TEST(LinearLaw, NormalDashpotIsTheGivenFractionOfCritical) {
  double h[3] = {0, 0, 0};
  const double beta = 0.4, kn = 1e5;
  const ContactKinematics k = pressed(1e-5, {0.0, 0.0, -0.1});  // approaching at 0.1 m/s
  const ContactForce f = law(kn, 0.0, 0.5, beta).evaluate(k, h);
  // c_n = 2 beta sqrt(m_eff k_n) adds compression while approaching.
  const double expected = kn * 1e-5 + 2.0 * beta * std::sqrt(k.effective_mass * kn) * 0.1;
  EXPECT_NEAR(-f.on_first.z, expected, 1e-14 * expected);
}

TEST(ContactLawRegistry, LinearDeclaresParametersHistoryAndUpscaling) {
  const ContactLawInfo* info = find_contact_law("linear");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->history.size(), LinearLaw::history_size);
  ASSERT_EQ(info->parameters.size(), 4u);
  EXPECT_EQ(info->parameters[0].name, "kn_n_m");
  EXPECT_EQ(info->parameters[0].unit, "N/m");
  const ContactLawSetting base = test::linear(1e5, 4e4, 0.5, 0.1);
  const ContactLawSetting scaled = upscale(base, 3.0);
  const auto& l = std::get<LinearLaw>(scaled.law);
  // Stiffness ~ E* R scales with S; dimensionless ratios stay (dem-physics.md §5).
  EXPECT_DOUBLE_EQ(l.kn, 3e5);
  EXPECT_DOUBLE_EQ(l.ks, 1.2e5);
  EXPECT_EQ(l.friction, 0.5);
  EXPECT_EQ(l.damping_ratio_normal, 0.1);
  EXPECT_NE(describe_contact_laws().find("kn_n_m [N/m] (required)"), std::string::npos);
}

}  // namespace
}  // namespace dfc::dem
