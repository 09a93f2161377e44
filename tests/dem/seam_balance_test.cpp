// The seam balance (seam_balance.hpp): the weighted least-squares bond-load
// correction on a bond graph, and the laws' add_bond_load that takes a load
// onto a bond with its matching displacement.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/portable_random.hpp"
#include "dfc/dem/seam_balance.hpp"

namespace dfc::dem {
namespace {

/// r_i + Σ_b A_ib Δf_b: what is left on every particle after the corrections.
std::vector<Vec3> after_correction(std::vector<Vec3> residual, const std::vector<BondEnds>& bonds, const std::vector<Vec3>& correction) {
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    residual[bonds[b][0]] += correction[b];
    residual[bonds[b][1]] -= correction[b];
  }
  return residual;
}

double objective(const std::vector<Vec3>& correction, const std::vector<double>& conductance) {
  double sum = 0.0;
  for (std::size_t b = 0; b < correction.size(); ++b) sum += norm2(correction[b]) / conductance[b];
  return sum;
}

/// A 4 x 4 grid of particles with bonds between neighbours and across the
/// diagonals (cycles everywhere, so the correction is not forced bond by bond).
struct Grid {
  std::vector<BondEnds> bonds;
  std::vector<double> conductance;
  static constexpr std::size_t side = 4, particles = side * side;
  Grid() {
    const auto at = [](std::size_t i, std::size_t j) { return std::uint32_t(i * side + j); };
    for (std::size_t i = 0; i < side; ++i)
      for (std::size_t j = 0; j < side; ++j) {
        if (j + 1 < side) bonds.push_back({at(i, j), at(i, j + 1)});
        if (i + 1 < side) bonds.push_back({at(i, j), at(i + 1, j)});
        if (i + 1 < side && j + 1 < side) bonds.push_back({at(i, j), at(i + 1, j + 1)});
      }
    // Bonds of the middle column "seam" weighted as seam bonds.
    for (const auto& b : bonds) conductance.push_back(b[0] % side == 1 && b[1] % side == 2 ? seam_bond_conductance : 1.0);
  }
};

std::vector<Vec3> random_residual(std::size_t n, std::uint64_t seed) {
  PortableRandom rng(seed);
  std::vector<Vec3> r(n);
  for (auto& v : r) v = {rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
  return r;
}

// With one particle held by a wall, every other particle's out-of-balance
// force is cancelled (to the solver's relative 1e-12, here 1e-10 in N of
// forces of order 1), and the held one takes the total: bond loads are
// internal forces, so the sum over all particles is unchanged.
TEST(SeamBalance, CancelsEveryFreeParticlesForceAndLeavesTheTotalOnTheHeldOne) {
  const Grid grid;
  const std::vector<Vec3> residual = random_residual(Grid::particles, 7);
  std::vector<bool> held(Grid::particles, false);
  held[0] = true;
  const BondNetworkBalance balance = balance_bond_network(Grid::particles, grid.bonds, grid.conductance, residual, held);
  const std::vector<Vec3> left = after_correction(residual, grid.bonds, balance.correction);
  Vec3 total;
  for (const auto& r : residual) total += r;
  for (std::size_t i = 1; i < Grid::particles; ++i) EXPECT_LT(norm(left[i]), 1e-10) << "particle " << i;
  EXPECT_LT(norm(left[0] - total), 1e-10);
  EXPECT_LT(balance.residual_after, 1e-9);
  EXPECT_GT(balance.residual_before, 1.0);
}

// The correction is the least-squares one: any other correction that
// balances the same particles differs from it by a self-equilibrated set of
// bond loads (a loop of equal loads around a cycle), and every such change
// raises Σ |Δf_b|²/c_b.
TEST(SeamBalance, TheCorrectionIsTheLeastWeightedChangeThatBalances) {
  const Grid grid;
  const std::vector<Vec3> residual = random_residual(Grid::particles, 11);
  std::vector<bool> held(Grid::particles, false);
  held[Grid::particles - 1] = true;
  const BondNetworkBalance balance = balance_bond_network(Grid::particles, grid.bonds, grid.conductance, residual, held);
  const double best = objective(balance.correction, grid.conductance);
  // The triangle (0,1), (1,5), (0,5) of the grid: bond indices found by ends.
  const auto index = [&](std::uint32_t a, std::uint32_t b) {
    for (std::size_t k = 0; k < grid.bonds.size(); ++k)
      if (grid.bonds[k][0] == a && grid.bonds[k][1] == b) return k;
    return grid.bonds.size();
  };
  const std::size_t ab = index(0, 1), bc = index(1, 5), ac = index(0, 5);
  ASSERT_LT(std::max({ab, bc, ac}), grid.bonds.size());
  for (const Vec3 loop : {Vec3{1e-3, 0.0, 0.0}, Vec3{0.0, -2e-3, 0.0}, Vec3{0.0, 0.0, 5e-4}}) {
    std::vector<Vec3> other = balance.correction;
    other[ab] += loop;  // on 0, off 1
    other[bc] += loop;  // on 1, off 5
    other[ac] -= loop;  // on 5, off 0: the loop adds nothing to any particle
    const std::vector<Vec3> left = after_correction(residual, grid.bonds, other);
    for (std::size_t i = 0; i + 1 < Grid::particles; ++i) EXPECT_LT(norm(left[i]), 1e-10);
    EXPECT_GT(objective(other, grid.conductance), best);
  }
}

// A component of the bond graph that no wall holds cannot pass its total on:
// each of its particles keeps the component's mean force.
TEST(SeamBalance, AComponentNoWallHoldsKeepsItsMeanOnEveryParticle) {
  const std::vector<BondEnds> bonds{{0, 1}, {1, 2}, {2, 0}, {3, 4}};
  const std::vector<double> conductance(bonds.size(), 1.0);
  const std::vector<Vec3> residual{{3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, {0.0, 0.0, -6.0}, {1.0, 0.0, 0.0}, {-1.0, 2.0, 0.0}};
  const BondNetworkBalance balance = balance_bond_network(5, bonds, conductance, residual, std::vector<bool>(5, false));
  const std::vector<Vec3> left = after_correction(residual, bonds, balance.correction);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_LT(norm(left[i] - Vec3{1.0, 1.0, -2.0}), 1e-12);
  for (std::size_t i = 3; i < 5; ++i) EXPECT_LT(norm(left[i] - Vec3{0.0, 1.0, 0.0}), 1e-12);
}

TEST(SeamBalance, TheBandReachesTheGivenNumberOfBondHops) {
  const std::vector<BondEnds> chain{{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}};
  std::vector<bool> seeds(6, false);
  seeds[0] = true;
  const std::vector<bool> band = within_bond_hops(6, chain, seeds, 3);
  EXPECT_EQ(band, (std::vector<bool>{true, true, true, true, false, false}));
}

// add_bond_load: the bond then returns its old force plus the added one (a
// step without motion), and holds the displacement its stiffness gives that
// load, so the next motion loads it as any other bond. Unequal spheres and
// an oblique normal, so that R_min, R1 + R2 and the in-plane split all count.
// 1e-12 relative: a few products and quotients of doubles.
ContactKinematics oblique_pair() {
  ContactKinematics k;
  const Vec3 n{0.36, -0.48, 0.8};
  k.normal = n;
  k.overlap = -2e-6;
  k.effective_mass = 1e-6;
  k.radius_first = 0.3e-3;
  k.radius_second = 0.55e-3;
  k.dt = 1e-8;
  return k;
}

TEST(SeamBalance, ASoftBondTakesTheAddedLoadWithItsElasticElongation) {
  const ContactLawSetting setting = make_contact_law({{"law", "soft_bond"}, {"sb_emod_pa", 2.8e9}, {"sb_rmul", 1.0}, {"sb_ten_pa", 1e12}, {"sb_coh_pa", 1e12}});
  ASSERT_TRUE(setting.can_add_bond_load());
  const auto& law = std::get<SoftBondLaw>(setting.law);
  const ContactKinematics k = oblique_pair();
  std::vector<double> h(SoftBondLaw::history_size, 0.0);
  set_bond_state(h.data(), BondState::intact);
  const Vec3 added{0.02, 0.05, -0.07};
  setting.add_bond_load(h.data(), k, added);
  const Vec3 force = law.evaluate(k, h.data()).on_first;
  EXPECT_LT(norm(force - added), 1e-12 * norm(added));
  const double area = std::numbers::pi * 0.3e-3 * 0.3e-3, kn = 2.8e9 / 0.85e-3;
  EXPECT_NEAR(h[SoftBondLaw::elongation_column], dot(added, k.normal) / (kn * area), 1e-12 * std::abs(dot(added, k.normal) / (kn * area)));
}

TEST(SeamBalance, ADamageBondTakesTheAddedLoadThroughItsElasticDisplacements) {
  const ContactLawSetting setting =
      make_contact_law({{"law", "damage_bond"}, {"emod_pa", 1e9}, {"bond_emod_pa", 2.8e9}, {"bond_kratio", 2.0}, {"bond_rmul", 0.8}, {"ten_pa", 1e12},
                        {"com_pa", 1e12}, {"coh_pa", 1e12}, {"ucn_m", 1.0}, {"ucs_m", 1.0}, {"theta_c_rad", 1.0}});
  ASSERT_TRUE(setting.can_add_bond_load());
  const auto& law = std::get<DamageBondLaw>(setting.law);
  const ContactKinematics k = oblique_pair();
  std::vector<double> h(DamageBondLaw::history_size, 0.0);
  set_bond_state(h.data(), BondState::damaged);
  h[DamageBondLaw::damage] = 0.25;  // a damaged bond: (1 - D) scales its stiffness
  const Vec3 added{-0.01, 0.03, 0.04};
  setting.add_bond_load(h.data(), k, added);
  const Vec3 force = law.evaluate(k, h.data()).on_first;
  EXPECT_LT(norm(force - added), 1e-12 * norm(added));
  const double area = std::numbers::pi * std::pow(0.8 * 0.3e-3, 2), kn = 2.8e9 / 0.85e-3;
  EXPECT_NEAR(h[DamageBondLaw::opening], dot(added, k.normal) / (0.75 * kn * area), 1e-12 * std::abs(dot(added, k.normal) / (0.75 * kn * area)));
}

TEST(SeamBalance, OnlyLawsWhoseBondKeepsItsLoadInHistoryCanTakeOne) {
  EXPECT_FALSE(make_contact_law({{"law", "linear"}, {"kn_n_m", 1e5}, {"ks_n_m", 1e5}}).can_add_bond_load());
  EXPECT_FALSE(make_contact_law({{"law", "linear_pbond"}, {"emod_pa", 1e9}, {"pb_emod_pa", 1e9}, {"pb_ten_pa", 1e6}, {"pb_coh_pa", 1e6}}).can_add_bond_load());
}

}  // namespace
}  // namespace dfc::dem
