// The `linear` law as a pure function (docs/theory/dem_contact_laws.md §2.3) and its registry entry.
#include <cmath>
#include <numbers>
#include <vector>

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

LinearLaw law(double kn, double ks, double mu, double beta = 0.0, double beta_shear = 0.0) {
  return {.kn = kn, .ks = ks, .friction = mu, .damping_ratio_normal = beta, .damping_ratio_shear = beta_shear};
}

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

TEST(LinearLaw, ShearDashpotAddsTheGivenFractionOfCriticalWhileTheContactSticks) {
  const double kn = 1e5, ks = 4e4, beta = 0.3;
  const LinearLaw l = law(kn, ks, 10.0, 0.0, beta);  // mu F_n = 10 N: far from sliding
  double h[3] = {0, 0, 0};
  const ContactKinematics k = pressed(1e-5, {0.02, -0.01, 0.5});  // opening along n = z, v_t = (0.02, -0.01, 0)
  const ContactForce f = l.evaluate(k, h);
  // Reference §2.3: c_s = 2 beta_s sqrt(m k_s). The spring takes k_s v_t dt
  // (stored), the dashpot c_s v_t (not stored: it has no memory); both drag
  // the first body along v_t. The normal part has no dashpot here (beta_n = 0).
  const double c_s = 2.0 * beta * std::sqrt(k.effective_mass * ks);
  const double spring_x = ks * k.dt * 0.02, spring_y = ks * k.dt * -0.01;
  // A few roundings of terms of one sign: 1e-15 relative.
  EXPECT_NEAR(f.on_first.x, spring_x + c_s * 0.02, 1e-15 * std::abs(c_s * 0.02));
  EXPECT_NEAR(f.on_first.y, spring_y + c_s * -0.01, 1e-15 * std::abs(c_s * 0.01));
  EXPECT_EQ(f.on_first.z, -kn * 1e-5);
  EXPECT_NEAR(h[0], spring_x, 1e-15 * spring_x);
  EXPECT_NEAR(h[1], spring_y, 1e-15 * -spring_y);
  // Without the dashpot the same step gives the spring alone: the term is the dashpot's.
  double undamped[3] = {0, 0, 0};
  EXPECT_NEAR(law(kn, ks, 10.0, 0.0, 0.0).evaluate(k, undamped).on_first.x, spring_x, 1e-15 * spring_x);
}

TEST(LinearLaw, ShearDashpotIsCutWhileTheContactSlidesSoTheTangentialForceStaysAtTheCoulombLimit) {
  // Slip-cut (PFC dp_mode 2, as LAMMPS and LIGGGHTS bound spring + dashpot):
  // a sliding contact carries mu F_n, not mu F_n + c_s |v_t|.
  const LinearLaw l = law(1e5, 5e4, 0.3, 0.0, 0.5);
  double h[3] = {0, 0, 0};
  const ContactKinematics sliding = pressed(1e-5, {0.01, 0.0, 0.0});  // F_n = 1 N, cap 0.3 N, +0.05 N per step
  ContactForce f{};
  for (int s = 0; s < 20; ++s) f = l.evaluate(sliding, h);
  EXPECT_NEAR(f.on_first.x, 0.3, 1e-15);  // one scaling at the cap
  EXPECT_NEAR(h[0], 0.3, 1e-15);
  // Reversing the slip unloads the spring from the cap: it sticks again, and the dashpot is back.
  const ContactKinematics back = pressed(1e-5, {-0.01, 0.0, 0.0});
  f = l.evaluate(back, h);
  const double c_s = 2.0 * 0.5 * std::sqrt(back.effective_mass * 5e4);
  EXPECT_NEAR(f.on_first.x, 0.25 - c_s * 0.01, 1e-15);
}

TEST(LinearLaw, ShearDashpotGivesTheLogarithmicDecrementOfADampedOscillator) {
  // A body of mass m on a fixed one, held in contact (mu large, no slip),
  // displaced tangentially and released: m x'' = -k_s x - c_s x', whose
  // successive maxima fall by exp(-2 pi beta / sqrt(1 - beta^2)) (damped
  // harmonic oscillator; c_s = 2 beta sqrt(m k_s) is beta of critical,
  // dem_contact_laws.md §2.3). Stepped as the integrator does (leapfrog: the law sees
  // the half-step velocity, then the velocity takes the force). With 2000
  // steps a period the scheme's error in the decrement is of order
  // (omega dt)^2 ~ 1e-5; 1e-3 relative is safe and fails for a dashpot off by 0.2 %.
  const double ks = 1e4, beta = 0.1, m = 1e-3;
  const LinearLaw l = law(1e5, ks, 1e3, 0.0, beta);
  const double dt = 2.0 * std::numbers::pi / std::sqrt(ks / m) / 2000.0;
  double h[3] = {1e-2, 0.0, 0.0};  // the spring starts loaded: the first body is displaced and released
  double velocity = 0.0;           // of the first body along x; the second body is fixed
  std::vector<double> spring;      // the spring force, -k_s x: its maxima are those of -x
  std::vector<double> peaks;
  for (int step = 0; step < 10000 && peaks.size() < 3; ++step) {
    ContactKinematics k = pressed(1e-5, {-velocity, 0.0, 0.0}, dt);
    k.effective_mass = m;
    velocity += l.evaluate(k, h).on_first.x / m * dt;
    spring.push_back(h[0]);
    const std::size_t n = spring.size();
    if (n >= 3 && spring[n - 2] > spring[n - 3] && spring[n - 2] >= spring[n - 1]) peaks.push_back(spring[n - 2]);
  }
  ASSERT_EQ(peaks.size(), 3u);
  const double decrement = 2.0 * std::numbers::pi * beta / std::sqrt(1.0 - beta * beta);
  EXPECT_NEAR(std::log(peaks[0] / peaks[1]), decrement, 1e-3 * decrement);
  EXPECT_NEAR(std::log(peaks[1] / peaks[2]), decrement, 1e-3 * decrement);
}

TEST(ContactLawRegistry, LinearDeclaresParametersHistoryAndUpscaling) {
  const ContactLawInfo* info = find_contact_law("linear");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->history.size(), LinearLaw::history_size);
  ASSERT_EQ(info->parameters.size(), 5u);
  EXPECT_EQ(info->parameters[4].key, "damping_ratio_shear");
  EXPECT_EQ(info->parameters[0].key, "kn_n_m");
  EXPECT_EQ(info->parameters[0].unit, "N/m");
  const ContactLawSetting base = test::linear(1e5, 4e4, 0.5, 0.1);
  const ContactLawSetting scaled = upscale(base, 3.0);
  const auto& l = std::get<LinearLaw>(scaled.law);
  // Stiffness ~ E* R scales with S; dimensionless ratios stay (docs/theory/upscaling_and_pcrm.md §1).
  EXPECT_DOUBLE_EQ(l.kn, 3e5);
  EXPECT_DOUBLE_EQ(l.ks, 1.2e5);
  EXPECT_EQ(l.friction, 0.5);
  EXPECT_EQ(l.damping_ratio_normal, 0.1);
  EXPECT_NE(describe_contact_laws().find("parameters: kn_n_m ks_n_m friction damping_ratio_normal damping_ratio_shear"), std::string::npos);
}

}  // namespace
}  // namespace dfc::dem
