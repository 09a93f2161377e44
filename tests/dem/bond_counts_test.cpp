// Simulation::bond_counts scans every pair row on every thread (each coupled
// advance reports it): its counts are those of a plain scan of the rows,
// whatever the thread count.
#include <gtest/gtest.h>

#include "dem_test_support.hpp"

namespace dfc::dem {
namespace {

TEST(BondCounts, EveryThreadCountCountsWhatTheRowsHold) {
  // A cubic lattice of 12^3 touching spheres: 3 x 12^2 x 11 = 4 752 bonds
  // between face neighbours (above the 2 048 pairs from which loops run in
  // parallel), and unbonded candidates (the face-diagonal neighbours, 0.83 mm
  // apart, within the 1 mm skin).
  const auto law = make_contact_law({{"law", "linear_pbond"}, {"emod_pa", 1e6}, {"pb_emod_pa", 1e6}, {"pb_ten_pa", 1e12},
                                     {"pb_coh_pa", 1e12}, {"bond_gap_m", 1e-5}});
  for (const int threads : {1, 2}) {
    Simulation sim(SimulationSettings{.particle_law = law, .gravity = {}, .local_damping = 0.0, .skin = 1e-3, .threads = threads});
    const int n = 12;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) sim.add_sphere((i * n + j) * n + k, {2e-3 * i, 2e-3 * j, 2e-3 * k}, 1e-3, 2650);
    sim.run(1, 1e-8);
    BondCounts scan;
    const PairContacts& pairs = sim.pair_contacts();
    ASSERT_GT(pairs.size(), 2048u);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const BondState s = bond_state(pairs.history.data() + k * pairs.stride);
      scan.intact += s == BondState::intact;
      scan.damaged += s == BondState::damaged;
      scan.broken_tension += s == BondState::broken_tension;
      scan.broken_shear += s == BondState::broken_shear;
    }
    const BondCounts counted = sim.bond_counts();
    EXPECT_EQ(counted.intact, 3 * n * n * (n - 1)) << threads << " thread(s)";
    EXPECT_EQ(counted.intact, scan.intact);
    EXPECT_EQ(counted.damaged, scan.damaged);
    EXPECT_EQ(counted.broken_tension, scan.broken_tension);
    EXPECT_EQ(counted.broken_shear, scan.broken_shear);
    EXPECT_GT(pairs.size(), std::size_t(scan.intact));  // unbonded candidates were scanned too
  }
}

}  // namespace
}  // namespace dfc::dem
