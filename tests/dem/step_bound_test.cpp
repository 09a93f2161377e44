// The per-particle stiffness bound of the critical time step (timestep.hpp,
// dem.timestep.stiffness_bound). Three claims, each against a closed form:
//
// 1. A law's stiffness_bound(r) bounds every contact a sphere of radius r can
//    have, whatever its partner's radius, facets included (the stiffness the
//    law shows, read from one force as in law_stiffness_test.cpp).
// 2. On a graded body the per-particle step is sqrt(r_max / r_min) times the
//    largest-radius one, and the same on equal spheres.
// 3. The step keeps an undamped graded body stable: a periodic chain of
//    large and small spheres (R = 2 r) conserves its energy at the scenarios'
//    fraction 0.3, and its stability limit, known in closed form, is where
//    the bound says it is.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"
#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {
namespace {

constexpr double strong = 1e12;  // Pa, strengths no step here reaches

nlohmann::json damage_bond(double friction) {
  return {{"law", "damage_bond"}, {"emod_pa", 1.7e9}, {"kratio", 5}, {"bond_emod_pa", 1.7e9}, {"bond_kratio", 5}, {"bond_rmul", 1.0},
          {"friction", friction}, {"ten_pa", strong}, {"com_pa", strong}, {"coh_pa", strong}, {"ucn_m", 1.0}, {"ucs_m", 1.0},
          {"theta_c_rad", 1.0}};
}

ContactKinematics touching(double radius_first, double radius_second, double overlap, double normal_velocity) {
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = overlap;
  k.relative_velocity = {0.0, 0.0, normal_velocity};
  k.effective_mass = 1e-5;
  k.radius_first = radius_first;
  k.radius_second = radius_second;
  k.dt = 1e-6;
  return k;
}

/// N/m: the linear contact's F/δ (bond broken, in overlap) plus the bond's
/// N/(v_n dt) after one step of opening (bond intact): the two springs a
/// damaged bond in contact has at once.
template <class Law>
double normal_stiffness(const Law& law, double radius_first, double radius_second) {
  constexpr double overlap = 1e-9, rate = 1e-3;
  std::vector<double> history(Law::history_size, 0.0);
  set_bond_state(history.data(), BondState::broken_shear);
  const double contact = -law.evaluate(touching(radius_first, radius_second, overlap, 0.0), history.data()).on_first.z / overlap;
  std::fill(history.begin(), history.end(), 0.0);
  set_bond_state(history.data(), BondState::intact);
  const double bond = law.evaluate(touching(radius_first, radius_second, -1e-9, rate), history.data()).on_first.z / (rate * 1e-6);
  return contact + bond;
}

// Radii over two decades each way, and a facet (radius 0: the ball alone).
// 1e-12 relative: the bound and the law's stiffness are a few products and
// one quotient each; where they meet (a facet, equal radii for the bond) they
// may differ by rounding only.
TEST(StepBound, AtASpheresOwnRadiusItBoundsEveryContactItCanHave) {
  const auto law = std::get<DamageBondLaw>(make_contact_law(damage_bond(0.5)).law);
  int checked = 0;
  for (const double own : {1e-5, 3e-5, 1e-4, 3e-4, 1e-3})
    for (const double partner : {0.0, 1e-6, 1e-5, 2e-5, 5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 1e-2, 1e-1}) {
      const double k = normal_stiffness(law, own, partner);
      EXPECT_LE(k, law.stiffness_bound(own).normal * (1.0 + 1e-12)) << "r " << own << ", partner " << partner;
      ++checked;
    }
  EXPECT_EQ(checked, 55);
  // The bound is reached by a facet contact: it is not looser than it must be.
  EXPECT_NEAR(normal_stiffness(law, 1e-4, 0.0), law.stiffness_bound(1e-4).normal, 1e-12 * law.stiffness_bound(1e-4).normal);
}

Simulation two_sizes(double small, double large, StepBound which) {
  Simulation sim(SimulationSettings{.particle_law = make_contact_law(damage_bond(0.5)), .gravity = {}, .local_damping = 0.0, .step_bound = which});
  sim.add_sphere(1, {0, 0, 0}, small, 2650);
  sim.add_sphere(2, {1, 0, 0}, large, 2650);
  return sim;
}

// Both steps are set by the small sphere's mass; the stiffness is that of
// radius r_min or r_max, k ∝ r: the ratio is sqrt(r_max / r_min) to rounding.
TEST(StepBound, PerParticleStepIsTheSquareRootOfTheRadiusRatioLarger) {
  for (const double ratio : {1.0, 2.0, 6.23}) {
    const double per_particle = two_sizes(1e-4, ratio * 1e-4, StepBound::per_particle).critical_timestep();
    const double largest = two_sizes(1e-4, ratio * 1e-4, StepBound::largest_radius).critical_timestep();
    EXPECT_NEAR(per_particle / largest, std::sqrt(ratio), 1e-12) << "r_max / r_min = " << ratio;
  }
}

// The cached step follows a change of radii.
TEST(StepBound, TheStepFollowsTheRadii) {
  Simulation sim = two_sizes(1e-4, 2e-4, StepBound::per_particle);
  const double before = sim.critical_timestep();
  sim.particles_for_edit().set_radius(0, 0.5e-4);
  EXPECT_NEAR(sim.critical_timestep() / before, 0.5, 1e-12);  // dt ∝ r_min
}

// --- A graded chain ---------------------------------------------------------------
// Spheres R = 2r alternate along x in a cell periodic along x, each pressed
// into its two neighbours by δ0, set moving along x: the centres stay on one
// line, so the motion is exactly one-dimensional and the closed form holds.
// Frictionless unbonded damage_bond contacts (its bond modulus negligible, so
// the bound is the contact's alone): F = k δ with k = π E r² / (R + r) =
// k_r / 3, k_r = π E r the bound at r. The chain's stiffest (optical) mode has
// ω² = 2k (1/m_r + 1/m_R) = (3/4) k_r / m_r: the leapfrog is stable below
// 2/ω = 2.309 sqrt(m_r / k_r) = 2.309 dt_crit(per_particle), against 3.27
// dt_crit(largest_radius). δ0 keeps every contact closed (the motion's
// amplitude is about 1 % of it).

constexpr double r_small = 0.5e-3, r_large = 1e-3, overlap0 = 0.01 * r_small;
constexpr int spheres = 16;
constexpr double spacing = r_small + r_large - overlap0;
constexpr double emod = 1.7e9;

struct Chain {
  Simulation sim;
  PeriodicCell cell;
};

Chain graded_chain() {
  nlohmann::json law = damage_bond(0.0);
  law["bond_emod_pa"] = 1.0;
  Chain c{Simulation(SimulationSettings{.particle_law = make_contact_law(law), .gravity = {}, .local_damping = 0.0, .install_bonds_at_start = false}),
          PeriodicCell{.lo = {0, -0.01, -0.01}, .hi = {spheres * spacing, 0.01, 0.01}, .periodic = {true, false, false}, .strain_rate = {}}};
  for (int i = 0; i < spheres; ++i) c.sim.add_sphere(i, {(i + 0.5) * spacing, 0, 0}, i % 2 ? r_small : r_large, 2650);
  c.sim.set_periodic_cell(c.cell);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05);  // m/s: ω ≈ 1.2e6 /s, amplitude ≈ 4e-8 m ≈ 1 % of δ0
  ParticleStore& p = c.sim.particles_for_edit();
  double momentum = 0.0, mass = 0.0;
  for (std::size_t n = 0; n < p.size(); ++n) p.velocity[n] = {u(random), 0, 0};
  for (std::size_t n = 0; n < p.size(); ++n) momentum += p.mass[n] * p.velocity[n].x, mass += p.mass[n];
  for (std::size_t n = 0; n < p.size(); ++n) p.velocity[n].x -= momentum / mass;  // no drift of the whole chain
  return c;
}

/// Positions, velocities, radii and masses by particle id (a rebuild may reorder the slots).
struct State {
  std::vector<Vec3> position, velocity;
  std::vector<double> radius, mass;
};

State by_id(const ParticleStore& p) {
  State s{std::vector<Vec3>(p.size()), std::vector<Vec3>(p.size()), std::vector<double>(p.size()), std::vector<double>(p.size())};
  for (std::size_t n = 0; n < p.size(); ++n) {
    const auto id = std::size_t(p.id[n]);
    s.position[id] = p.position[n], s.velocity[id] = p.velocity[n], s.radius[id] = p.radius[n], s.mass[id] = p.mass[n];
  }
  return s;
}

/// J: Σ ½ k δ² over the chain's contacts (neighbours by id, minimum image).
double spring_energy(const PeriodicCell& cell, const State& s) {
  double energy = 0.0;
  for (std::size_t a = 0; a < s.radius.size(); ++a) {
    const std::size_t b = (a + 1) % s.radius.size();
    const double overlap = s.radius[a] + s.radius[b] - norm(cell.minimum_image(s.position[b] - s.position[a]));
    const double r = std::min(s.radius[a], s.radius[b]);
    if (overlap > 0.0) energy += 0.5 * std::numbers::pi * emod * r * r / (s.radius[a] + s.radius[b]) * overlap * overlap;
  }
  return energy;
}

/// Relative excursion max |E_n - E_0| / (E_0 - U_0) of the leapfrog's
/// conserved energy E_n = Σ ½ m v_{n-½} v_{n+½} + U(x_n) (exact for linear
/// springs; Hairer, Lubich & Wanner 2003 on the Störmer–Verlet scheme), over
/// the vibration's energy (U_0: the springs' at rest; on a ring the term
/// linear in the displacements sums to zero); infinity once it grows without
/// bound. `steps` steps of fraction x dt_crit(per_particle).
double energy_excursion(double fraction, int steps) {
  Chain c = graded_chain();
  const double dt = fraction * c.sim.critical_timestep();
  const double at_rest = spring_energy(c.cell, by_id(c.sim.particles()));
  double e0 = 0.0, worst = 0.0;
  for (int s = 0; s <= steps; ++s) {
    const State before = by_id(c.sim.particles());
    try {
      c.sim.step(dt);
    } catch (const SolverError&) {
      return std::numeric_limits<double>::infinity();  // an overlap beyond the guard: blown up
    }
    const State after = by_id(c.sim.particles());
    double energy = spring_energy(c.cell, before);
    for (std::size_t n = 0; n < before.mass.size(); ++n) energy += 0.5 * before.mass[n] * before.velocity[n].x * after.velocity[n].x;
    if (s == 0) e0 = energy;
    worst = std::max(worst, std::abs(energy - e0) / (e0 - at_rest));
    if (!(worst < 1e3)) return std::numeric_limits<double>::infinity();
  }
  return worst;
}

// At the fraction the open-pile scenarios use (0.3), over 20 000 steps
// (about 800 periods of the stiffest mode): the vibration keeps its energy to
// 1e-6. What remains is round-off in E_n (a difference of terms 1e3 times
// larger, each to 1e-16 relative, summed over the steps) and the springs'
// non-linearity in δ, which the aligned chain does not have.
TEST(StepBound, AGradedChainKeepsItsEnergyAtTheScenariosFraction) {
  EXPECT_LT(energy_excursion(0.3, 20000), 1e-6);
}

// Just below the closed-form limit 2.309 dt_crit the energy stays bounded
// (the leapfrog's shadow energy swings widely near its limit, hence 1);
// just above it, it grows without bound: the bound is conservative by the
// chain's factor (k = k_r / 3, two neighbours), no more and no less.
TEST(StepBound, TheChainBecomesUnstableWhereTheClosedFormSays) {
  EXPECT_LT(energy_excursion(2.25, 20000), 1.0);
  EXPECT_EQ(energy_excursion(2.37, 20000), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace dfc::dem
