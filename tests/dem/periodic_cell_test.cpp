// The periodic cell: minimum-image contacts across a face, wrapping with
// history and bonds kept, and the Love–Weber stress of a static lattice.
#include <cmath>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/cell_stress.hpp"

namespace dfc::dem {
namespace {

constexpr double unit = 0x1.0p-12;  // m; every coordinate below is a multiple: differences are exact
constexpr double cell_edge = 64 * unit;
constexpr double radius = 4 * unit;

PeriodicCell cube(double edge) { return PeriodicCell{.lo = {0, 0, 0}, .hi = {edge, edge, edge}, .periodic = {true, true, true}, .strain_rate = {}}; }

Simulation pair(const ContactLawSetting& law, Vec3 a, Vec3 b, bool periodic, double skin = 0.5 * unit) {
  Simulation sim(SimulationSettings{.particle_law = law, .gravity = {}, .local_damping = 0.0, .skin = skin, .threads = 1});
  sim.add_sphere(1, a, radius, 2650);
  sim.add_sphere(2, b, radius, 2650);
  if (periodic) sim.set_periodic_cell(cube(cell_edge));
  return sim;
}

const ParticleStore& step_once(Simulation& sim, Vec3 velocity_of_1) {
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.velocity[i] = p.id[i] == 1 ? velocity_of_1 : Vec3{};
    p.angular_velocity[i] = p.id[i] == 1 ? Vec3{0, 0, 30.0} : Vec3{};
  }
  sim.step(1e-7);
  return sim.particles();
}

std::size_t slot(const ParticleStore& p, std::int64_t id) { return p.id[0] == id ? 0 : 1; }

TEST(PeriodicCell, PairAcrossAFaceGetsTheSameForceAsInsideTheCell) {
  // Overlap 1 unit (r/4), sliding and spinning: normal, tangential force and
  // both moments (the second body's lever arm comes from its image).
  const ContactLawSetting law = test::linear(1e5, 5e4, 0.5, 0.2);
  Simulation across = pair(law, {2 * unit, 20 * unit, 20 * unit}, {cell_edge - 5 * unit, 21 * unit, 20 * unit}, true);
  Simulation inside = pair(law, {32 * unit, 20 * unit, 20 * unit}, {25 * unit, 21 * unit, 20 * unit}, true);
  const ParticleStore& a = step_once(across, {0, 0.01, 0});
  const ParticleStore& b = step_once(inside, {0, 0.01, 0});
  for (const std::int64_t id : {1, 2}) {
    const std::size_t i = slot(a, id), j = slot(b, id);
    // The branch vectors are bit-identical (exact coordinates); the contact
    // point is stored in absolute coordinates, so its lever arm (x + t) - x
    // rounds differently 30 units further along: the difference stays at
    // round-off of the force, 1e-13 of it here.
    // Moments are compared on the scale f r (a lever arm taken from the wrong
    // image would be off by f L, 16 times that).
    const double f = norm(b.force[j]);
    EXPECT_GT(f, 0.0);
    EXPECT_LT(norm(a.force[i] - b.force[j]), 1e-13 * f) << "particle " << id;
    EXPECT_LT(norm(a.moment[i] - b.moment[j]), 1e-13 * f * radius) << "particle " << id;
  }
  EXPECT_EQ(across.bond_counts().intact, 0);
}

TEST(PeriodicCell, PairTooCloseForTheCellIsRefused) {
  Simulation sim(SimulationSettings{.particle_law = test::linear(1e5, 5e4), .gravity = {}, .local_damping = 0.0, .skin = unit, .threads = 1});
  sim.add_sphere(1, {unit, unit, unit}, radius, 2650);
  EXPECT_THROW(sim.set_periodic_cell(cube(16 * unit)), UserError);  // needs 2 (2 r + skin) = 18 units
}

/// A pair sliding past each other while drifting in +x through the face many
/// times; the same pair in open space is the reference.
struct Drift {
  Simulation sim;
  std::vector<double> shear;  ///< |tangential force| per step
};

Drift drift(const ContactLawSetting& law, bool periodic, int steps) {
  Drift d{pair(law, {60 * unit, 20 * unit, 20 * unit}, {60 * unit, 20 * unit, 27.5 * unit}, periodic, 0.05 * unit), {}};
  ParticleStore& p = d.sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = {20.0, p.id[i] == 1 ? 0.005 : -0.005, 0.0};
  for (int s = 0; s < steps; ++s) {
    d.sim.step(1e-6);
    EXPECT_EQ(d.sim.pair_contacts().size(), 1u) << "step " << s;
    if (d.sim.pair_contacts().size() != 1) break;
    const Vec3 f = d.sim.contact_outputs().force.at(0);
    d.shear.push_back(std::hypot(f.x, f.y));
  }
  return d;
}

TEST(PeriodicCell, WrappedParticlesKeepTheirContactHistory) {
  // 20 m/s x 1e-6 s per step: the pair crosses the 15.6 mm cell twice in
  // 1500 steps. Soft normal spring (5 N/m) so the pair stays in contact that
  // long; friction high so the tangential spring only grows: a history lost
  // at a wrap would drop it to 0.
  const ContactLawSetting law = test::linear(5.0, 5.0, 10.0);
  const Drift periodic = drift(law, true, 1500);
  const Drift open = drift(law, false, 1500);
  EXPECT_GT(periodic.sim.rebuild_count(), 100u);
  for (const double x : {periodic.sim.particles().position[0].x, periodic.sim.particles().position[1].x}) EXPECT_LT(x, cell_edge + unit);
  ASSERT_EQ(periodic.shear.size(), open.shear.size());
  EXPECT_GT(open.shear.back(), 5e-6);  // at most 0.01 m/s x 1.5 ms x 5 N/m = 7.5e-5 N; the spheres roll, taking up part of the slip
  // Positions differ by whole cell lengths, so round-off differs in the last bits only.
  for (std::size_t s = 0; s < open.shear.size(); ++s) EXPECT_NEAR(periodic.shear[s], open.shear[s], 1e-9 * open.shear.back()) << "step " << s;
}

TEST(PeriodicCell, BondAcrossTheFaceIsInstalledAndSurvivesWraps) {
  const ContactLawSetting law = make_contact_law({{"law", "linear_pbond"}, {"emod_pa", 1e6}, {"pb_emod_pa", 1e6}, {"pb_ten_pa", 1e12},
                                                  {"pb_coh_pa", 1e12}, {"bond_gap_m", 0.5 * unit}});
  // Surface gap 0.25 unit across the x face: bonded at the first rebuild.
  Simulation sim = pair(law, {cell_edge - 4 * unit, 20 * unit, 20 * unit}, {4.25 * unit, 20 * unit, 20 * unit}, true, 0.05 * unit);
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = {p.id[i] == 1 ? 20.0 : 20.01, 0.0, 0.0};
  for (int s = 0; s < 2000; ++s) sim.step(1e-6);
  EXPECT_GT(sim.rebuild_count(), 50u);
  EXPECT_EQ(sim.bond_counts().intact, 1);
  // The bond pulls the pair back together: their minimum-image gap stays near the start.
  const ParticleStore& q = sim.particles();
  const double gap = norm(sim.periodic_cell()->minimum_image(q.position[1] - q.position[0])) - 8 * unit;
  EXPECT_LT(std::abs(gap - 0.25 * unit), 0.25 * unit);
}

TEST(CellStress, ABondInstalledWithZeroLoadCountsInTheAffineStiffness) {
  // A bond installed with zero load (sample_preparation.hpp) carries no force
  // but resists the next strain with its whole stiffness: the servo's
  // stiffness K_a must count it. Left out (it was), K_a was 0 after the
  // installation and the servo strained the bonded cell at its cap.
  const ContactLawSetting law = make_contact_law({{"law", "linear_pbond"}, {"emod_pa", 1e6}, {"pb_emod_pa", 1e6}, {"pb_ten_pa", 1e12},
                                                  {"pb_coh_pa", 1e12}, {"bond_gap_m", 0.5 * unit}});
  // Along x, surface gap 0.25 unit: bonded at the first rebuild, with zero load.
  Simulation sim = pair(law, {20 * unit, 20 * unit, 20 * unit}, {28.25 * unit, 20 * unit, 20 * unit}, true);
  sim.install_bonds_now();
  sim.step(1e-9);
  ASSERT_EQ(sim.bond_counts().intact, 1);
  const CellStress s = measure_cell_stress(sim);
  EXPECT_EQ(s.sigma[0][0], 0.0);
  // k_n d_x^4 / |d|^2 / V with the law's normal stiffness bound: the branch
  // lies along x, so only K_xx is non-zero.
  const double d = 8.25 * unit, kn = law.stiffness_bound(radius).normal;
  EXPECT_NEAR(s.affine_stiffness.x, kn * d * d / (cell_edge * cell_edge * cell_edge), 1e-12 * s.affine_stiffness.x);
  EXPECT_EQ(s.affine_stiffness.y, 0.0);
  EXPECT_EQ(s.affine_stiffness.z, 0.0);
}

TEST(CellStress, SimpleCubicLatticeUnderUniformCompressionMatchesTheClosedForm) {
  // n^3 spheres of radius r at pitch a = 2r - delta fill the cell n a: each
  // sphere has 6 contacts of force k delta along +-x, y, z; per sphere (volume
  // a^3) the three contacts it owns contribute k delta a each to one diagonal
  // term, so sigma_xx = sigma_yy = sigma_zz = k delta a / a^3 = k delta / a^2,
  // off-diagonal 0 (compression positive).
  const double k = 1e5, delta = 0.25 * unit, a = 2 * radius - delta;
  const int n = 4;
  Simulation sim(SimulationSettings{.particle_law = test::linear(k, 5e4), .gravity = {}, .local_damping = 0.0, .skin = 0.5 * unit, .threads = 1});
  std::int64_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int l = 0; l < n; ++l) sim.add_sphere(id++, {(i + 0.5) * a, (j + 0.5) * a, (l + 0.5) * a}, radius, 2650);
  sim.set_periodic_cell(cube(n * a));
  sim.step(1e-7);
  const CellStress s = measure_cell_stress(sim);
  const double expected = k * delta / (a * a);
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) {
      // Round-off of the n^3 x 3 summed terms: 1e-12 relative is ~1e4 ulps of margin.
      if (r == c) EXPECT_NEAR(s.sigma[r][c], expected, 1e-12 * expected);
      else EXPECT_NEAR(s.sigma[r][c], 0.0, 1e-12 * expected);
    }
  EXPECT_NEAR(cell_porosity(sim.particles(), *sim.periodic_cell()), 1.0 - 4.0 / 3.0 * M_PI * radius * radius * radius / (a * a * a), 1e-14);
}

}  // namespace
}  // namespace dfc::dem
