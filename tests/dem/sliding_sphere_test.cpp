// A sphere launched sliding on a frictional floor (classic rigid-body result,
// e.g. Goldstein / any dynamics text for a "bowling ball"): friction mu m g
// decelerates it and spins it up until it rolls, at v = 5/7 v0, after
// t* = 2 v0 / (7 mu g). Tests the Coulomb cap on a wall contact and the
// rotational degrees of freedom.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

TEST(SlidingSphere, FrictionIsCappedAtMuTimesNormalForceThenTheSphereRollsAtFiveSevenths) {
  constexpr double r = 1e-3, rho = 2650.0, kn = 1e5, mu = 0.3, g = 9.81, v0 = 0.1;
  const ContactLawSetting law = test::linear(kn, kn, mu);
  Simulation sim(SimulationSettings{.particle_law = law, .gravity = {0, 0, -g}, .local_damping = 0.0, .skin = 0.0, .threads = 1});
  sim.add_wall(make_wall("floor", make_plane_mesh({0, 0, 0}, {0, 0, 1}, 0.05), WallMotion::prescribed, law));
  const double mass = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  // Start at the static overlap m g / k_n so no normal oscillation disturbs the test.
  sim.add_sphere(7, {-0.01, -0.02, r - mass * g / kn}, r, rho);
  sim.particles_for_edit().velocity[0] = {v0, 0, 0};

  const double dt = 0.1 * sim.critical_timestep();
  const double t_star = 2.0 * v0 / (7.0 * mu * g);
  const auto slide_steps = std::int64_t(0.5 * t_star / dt);
  sim.run(slide_steps, dt);
  // Mid-slide: the floor carries |F_t| = mu F_n exactly (one scaling of the shear vector).
  const Vec3 f = sim.walls()[0].force;
  EXPECT_NEAR(std::hypot(f.x, f.y) / std::abs(f.z), mu, 1e-12);
  EXPECT_GT(f.x, 0.0);  // the sliding sphere drags the floor along +x

  sim.run(std::int64_t(2.0 * t_star / dt), dt);
  const ParticleStore& p = sim.particles();
  // Rolling: v = 5/7 v0 and omega r = v. The elastic shear spring leaves a small
  // oscillation about the rigid result (stick-slip micro-motion): 1 % allows for it.
  EXPECT_NEAR(p.velocity[0].x, 5.0 / 7.0 * v0, 0.01 * 5.0 / 7.0 * v0);
  EXPECT_NEAR(p.angular_velocity[0].y * r, p.velocity[0].x, 0.01 * p.velocity[0].x);
}

}  // namespace
}  // namespace dfc::dem
