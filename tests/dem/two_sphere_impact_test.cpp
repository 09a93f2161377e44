// Head-on impact of two equal spheres under the linear law without damping
// (Hertz-free spring contact: a half period of a harmonic oscillator).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/measurements.hpp"

namespace dfc::dem {
namespace {

constexpr double radius = 1e-3, density = 2650.0, kn = 1e5, approach_speed = 0.05;

struct ImpactResult {
  double energy_error = 0.0;  ///< (E_after - E_before) / E_before
  double duration_error = 0.0;   ///< (steps with a non-zero force x dt - t_c) / t_c
  double max_force_error = 0.0;  ///< max |F - kn overlap| / (kn overlap) during the impact
};

ImpactResult impact(double steps_per_contact) {
  Simulation sim = test::undamped(test::linear(kn, 0.1 * kn, 0.5));
  const double gap = 1e-6;
  sim.add_sphere(1, {-radius - 0.5 * gap, 0, 0}, radius, density);
  sim.add_sphere(2, {radius + 0.5 * gap, 0, 0}, radius, density);
  ParticleStore& p = sim.particles_for_edit();
  p.velocity[0] = {approach_speed, 0, 0};
  p.velocity[1] = {-approach_speed, 0, 0};
  const double m_eff = 0.5 * p.mass[0];
  const double contact_time = std::numbers::pi * std::sqrt(m_eff / kn);  // half period of sqrt(kn/m_eff)
  const double dt = contact_time / steps_per_contact;
  const double e0 = measure(sim).kinetic_energy;

  ImpactResult r;
  int in_contact = 0;
  const auto n_steps = int(3.0 * steps_per_contact + gap / (2 * approach_speed) / dt);
  for (int s = 0; s < n_steps; ++s) {
    // Overlap at the positions the force is about to be computed from.
    const ParticleStore& q = sim.particles();
    const double overlap = 2 * radius - norm(q.position[1] - q.position[0]);
    sim.step(dt);
    const double f = norm(sim.particles().force[0]);
    if (f > 0.0) {
      ++in_contact;
      r.max_force_error = std::max(r.max_force_error, std::abs(f - kn * overlap) / (kn * overlap));
    }
  }
  r.duration_error = (in_contact * dt - contact_time) / contact_time;
  r.energy_error = (measure(sim).kinetic_energy - e0) / e0;
  return r;
}

TEST(TwoSphereImpact, ForceIsNormalStiffnessTimesOverlapThroughoutTheImpact) {
  const ImpactResult r = impact(200);
  // F = k_n * overlap with the overlap from the same positions: rounding only.
  EXPECT_LT(r.max_force_error, 1e-9);
}

TEST(TwoSphereImpact, ContactLastsHalfAPeriodOfTheNormalSpring) {
  // t_c = pi sqrt(m_eff / k_n); counting whole steps errs by at most one dt = 0.1 % here.
  const ImpactResult r = impact(997.3);  // not an integer: the onset falls anywhere within a step
  RecordProperty("contact_duration_error", test::figure(r.duration_error));
  EXPECT_LT(std::abs(r.duration_error), 0.01) << "relative error of the contact duration " << r.duration_error;
}

TEST(TwoSphereImpact, EnergyIsConservedToSecondOrderInTheTimeStep) {
  // Leapfrog is symplectic: the energy error after the impact is O((dt/t_c)^2);
  // the force is continuous at contact onset, so no O(dt) term appears.
  const ImpactResult coarse = impact(50);
  const ImpactResult fine = impact(100);
  RecordProperty("energy_error_50", test::figure(coarse.energy_error));
  RecordProperty("energy_error_100", test::figure(fine.energy_error));
  const double bound = std::pow(std::numbers::pi / 50.0, 2);  // (omega dt)^2 at 50 steps per contact
  EXPECT_LT(std::abs(coarse.energy_error), bound);
  // Halving dt must cut the error by about 4 (second order); 3 allows for the
  // phase of the contact onset within a step.
  EXPECT_LT(std::abs(fine.energy_error), std::abs(coarse.energy_error) / 3.0 + 1e-12);
}

}  // namespace
}  // namespace dfc::dem
