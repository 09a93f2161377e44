// Bonds in a Simulation: installed at start within the bonding gap, kept
// (with their history) through neighbour-list rebuilds even when the pair
// separates beyond the Verlet skin, and counted by state.
#include <gtest/gtest.h>

#include "dem_test_support.hpp"

namespace dfc::dem {
namespace {

ContactLawSetting pbond(double tensile_strength, double gap) {
  return make_contact_law({{"law", "linear_pbond"}, {"emod_pa", 1e6}, {"pb_emod_pa", 1e6}, {"pb_ten_pa", tensile_strength},
                           {"pb_coh_pa", 1e12}, {"bond_gap_m", gap}});
}

Simulation two_spheres(const ContactLawSetting& law, double separation_speed) {
  Simulation sim(SimulationSettings{.particle_law = law, .gravity = {}, .local_damping = 0.0, .skin = 1e-6, .threads = 1});
  sim.add_sphere(7, {0, 0, 0}, 1e-3, 2650);
  sim.add_sphere(3, {0, 0, 2e-3 + 5e-5}, 1e-3, 2650);  // surface gap 50 um
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = {0, 0, p.id[i] == 3 ? separation_speed : -separation_speed};
  return sim;
}

double surface_gap(const Simulation& sim) {
  const auto& p = sim.particles();
  return norm(p.position[1] - p.position[0]) - p.radius[0] - p.radius[1];
}

TEST(BondPersistence, PairsWithinTheBondGapAreBondedAtStart) {
  Simulation bonded = two_spheres(pbond(1e12, 1e-4), 0.0);
  bonded.step(1e-7);
  EXPECT_EQ(bonded.bond_counts().intact, 1);
  Simulation apart = two_spheres(pbond(1e12, 4e-5), 0.0);  // 50 um gap > 40 um bonding gap
  apart.step(1e-7);
  EXPECT_EQ(apart.bond_counts().intact, 0);
}

TEST(BondPersistence, AfterBondsAreInstalledOnlyBondsAndPairsWithinTheSkinStayCandidates) {
  // Installing bonds searches to 1.001 x the bond gap (100 um here), far
  // beyond the 1 um skin. Spheres 7 and 3 are 50 um apart (bonded); 3 and 9
  // 100.05 um, found by that search but beyond the bond gap (and its 2e-12 m
  // round-off allowance): no bond, and beyond the skin, so no longer a
  // candidate once the bonds are in, as at every later rebuild.
  Simulation sim = two_spheres(pbond(1e12, 1e-4), 0.0);
  sim.add_sphere(9, {0, 0, 4e-3 + 5e-5 + 1.0005e-4}, 1e-3, 2650);
  sim.step(1e-9);
  EXPECT_EQ(sim.bond_counts().intact, 1);
  ASSERT_EQ(sim.pair_contacts().size(), 1u);
  const auto& p = sim.particles();
  EXPECT_EQ(p.id[sim.pair_contacts().first[0]] + p.id[sim.pair_contacts().second[0]], 10);  // the pair 3-7
}

/// Bonds installed in a touching simple cubic lattice of n^3 spheres of radius r.
std::int64_t lattice_bonds(double r, int n) {
  Simulation sim(SimulationSettings{.particle_law = pbond(1e12, 0.0), .gravity = {}, .local_damping = 0.0, .skin = 0.1 * r, .threads = 1});
  std::int64_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) sim.add_sphere(id++, {0.1 + 2 * r * i, 0.3 + 2 * r * j, 0.7 + 2 * r * k}, r, 2650);
  sim.step(1e-9);
  return sim.bond_counts().intact;
}

TEST(BondPersistence, TouchingSpheresAreBondedWhateverTheirSize) {
  // With bond_gap_m = 0, whether a touching pair is bonded used to depend on
  // the last bit of |x_j - x_i| - r_i - r_j: at r = 3.7 mm about half of the
  // lattice's contacts were lost to round-off. The bonding test allows a gap
  // of 1e-9 (r_i + r_j), far below any physical bond gap and far above round-off.
  for (const double r : {1e-3, 3.7e-3, 1.1e-4, 0.3}) EXPECT_EQ(lattice_bonds(r, 4), 3 * 4 * 4 * 3) << "r = " << r;
}

TEST(BondPersistence, BondSurvivesSeparationBeyondTheSkinAndPullsBack) {
  // Bond k = Ebar* / (2R) * pi R^2 = 1.57e3 N/m, m_eff = 5.5e-6 kg: the
  // pair opens by v_rel / omega = 1 / 1.7e4 = 59 um, far beyond the 1 um skin.
  Simulation sim = two_spheres(pbond(1e12, 1e-4), 0.5);
  const double dt = 1e-6, gap0 = surface_gap(sim);
  double widest = 0.0, closest_after_widest = 1.0;
  for (int s = 0; s < 400; ++s) {  // about one period (2 pi / omega = 370 us)
    sim.step(dt);
    const double opening = surface_gap(sim) - gap0;
    if (opening > widest) widest = opening, closest_after_widest = opening;
    closest_after_widest = std::min(closest_after_widest, opening);
  }
  // The spheres separated by many skins (so rebuilds dropped the pair from
  // the searched list), yet the unbreakable bond stayed and pulled them back.
  EXPECT_GT(widest, 10 * sim.skin());
  EXPECT_GT(sim.rebuild_count(), 5u);
  EXPECT_EQ(sim.bond_counts().intact, 1);
  EXPECT_LT(closest_after_widest, 0.2 * widest);
}

TEST(BondPersistence, BrokenBondStaysCountedAfterTheParticlesFlyApart) {
  Simulation sim = two_spheres(pbond(1e3, 1e-4), 0.5);
  for (int s = 0; s < 4000; ++s) sim.step(1e-6);
  const BondCounts c = sim.bond_counts();
  EXPECT_GT(surface_gap(sim), 100 * sim.skin());
  EXPECT_EQ(c.intact, 0);
  EXPECT_EQ(c.broken_tension, 1);
  EXPECT_EQ(c.broken_shear, 0);
}

TEST(BondPersistence, UnbondedLawHasNoBonds) {
  Simulation sim = two_spheres(test::linear(1e5, 1e5), 0.0);
  sim.step(1e-7);
  const BondCounts c = sim.bond_counts();
  EXPECT_EQ(c.intact + c.damaged + c.broken_tension + c.broken_shear, 0);
}

}  // namespace
}  // namespace dfc::dem
