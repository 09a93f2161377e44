// Periodic cell replication (pcrm_replication.hpp) and stress scaling
// (stress_scaling.hpp) on a small bonded REV of the chalk law of Ciantia et al. (2024).
#include <cmath>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/rev_preparation.hpp"
#include "dfc/dem/stress_scaling.hpp"

namespace dfc::dem {
namespace {

ContactLawSetting chalk() {
  // Ciantia et al. (2024) Table 1 (docs/references.md): E*, kappa*, strengths, u_c and theta_c (u_c, bond gap at S = 10).
  return make_contact_law({{"law", "damage_bond"}, {"emod_pa", 1.7e9}, {"kratio", 5}, {"friction", 0.5}, {"bond_emod_pa", 1.7e9},
                           {"bond_kratio", 5}, {"ten_pa", 1e6}, {"com_pa", 5e7}, {"coh_pa", 2e6}, {"ucn_m", 2e-4}, {"ucs_m", 2e-4},
                           {"theta_c_rad", 0.006}, {"bond_gap_m", 2.62e-4}});
}

SimulationSettings settings() {
  return SimulationSettings{.particle_law = chalk(), .gravity = {}, .local_damping = 0.7, .skin = 0.0, .threads = 1};
}

/// About 250 spheres of the chalk PSD at S = 10 in an 8 mm cell, at 100 kPa on
/// z and K0 = 0.5.
const PreparedRev& rev() {
  static const PreparedRev prepared = [] {
    RevSpec spec;
    spec.particles = {.radius_min = 3.275e-4, .radius_max = 9.025e-4, .porosity = 0.45, .multiplier = 1.6, .stages = 10, .relax_steps = 300, .seed = 5};
    spec.cell = {.lo = {}, .hi = {8e-3, 8e-3, 8e-3}, .periodic = {true, true, true}, .strain_rate = {}};
    spec.density = 2556;
    spec.consolidation.tolerance = 0.02;
    spec.consolidation.unbalanced_force_ratio = 0.05;
    spec.consolidation.loading = {.mode = CellLoading::Mode::anisotropic, .axis = 2, .stress = 1e5, .lateral_ratio = 0.5, .axial_rate = 0.0, .strain_rate = {}};
    spec.fraction_of_critical = 0.3;
    return prepare_rev(spec, settings(), "particles.rev");
  }();
  return prepared;
}

/// The replicated body in a periodic cell of `n` copies per axis.
Simulation tiled(int n) {
  const PreparedRev& r = rev();
  const Vec3 l = r.cell.length();
  const BedRegion box{.shape = BedRegion::Shape::box, .min = r.cell.lo, .max = r.cell.lo + double(n) * l};
  const ReplicatedBody body = replicate(r, box, 1.0, true);
  Simulation sim(settings());
  for (std::size_t k = 0; k < body.spheres.size(); ++k) sim.add_sphere(body.id[k], body.spheres[k].centre, body.spheres[k].radius, 2556);
  sim.seed_pair_history(body.archive(), true);
  sim.set_periodic_cell({.lo = box.min, .hi = box.max, .periodic = {true, true, true}, .strain_rate = {}});
  return sim;
}

TEST(Pcrm, TheRevCarriesItsReferenceStressInItsBonds) {
  const PreparedRev& r = rev();
  EXPECT_NEAR(r.stress.z, 1e5, 0.02 * 1e5);  // the servo's tolerance
  EXPECT_NEAR(r.stress.x, 0.5e5, 0.02 * 0.5e5);
  EXPECT_NEAR(r.stress.y, 0.5e5, 0.02 * 0.5e5);
  EXPECT_GT(r.bonds, std::int64_t(r.spheres.size()));  // coordination above 2
  for (const RevPair& p : r.pairs) EXPECT_LT(p.first, p.second);
}

TEST(Pcrm, ReplicatedTwiceEachWayTheBodyHasTheRevsStressAndEquilibrium) {
  // A 2 x 2 x 2 tiling of a periodic REV is the same infinite packing: every
  // sphere has the REV's neighbours, bonds and bond loads, so the cell stress
  // and the resultant of every sphere are the REV's (to round-off: sums in
  // another order). A seam (a pair across a copy face lost) would leave the
  // spheres next to it with a net force of a whole contact force.
  Simulation sim = tiled(2);
  const PreparedRev& r = rev();
  EXPECT_EQ(sim.particles().size(), 8 * r.spheres.size());
  sim.step(r.dt);
  const CellStress s = measure_cell_stress(sim);
  EXPECT_NEAR(s.sigma[2][2], r.stress.z, 1e-9 * r.stress.z);
  EXPECT_NEAR(s.sigma[0][0], r.stress.x, 1e-9 * r.stress.z);
  EXPECT_EQ(sim.bond_counts().intact, 8 * r.bonds);
  EXPECT_LT(measure(sim).unbalanced_force_ratio, 0.05);  // the REV's own tolerance
}

}  // namespace
}  // namespace dfc::dem

namespace dfc::dem {
namespace {

/// A bond loaded elastically for 50 steps (compression, shear in two
/// directions, bending, twist), then evaluated with no further motion.
template <class Law>
ContactForce loaded_bond(const Law& law, std::vector<double>& h, bool load) {
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = 1e-7;
  k.radius_first = k.radius_second = 1e-3;
  k.effective_mass = 1e-6;
  k.dt = 1e-6;
  if (load) {
    set_bond_state(h.data(), BondState::intact);
    k.relative_velocity = {1e-3, -5e-4, -2e-3};
    k.relative_angular_velocity = {0.05, -0.03, 0.02};
    for (int s = 0; s < 50; ++s) (void)law.evaluate(k, h.data());
  }
  k.relative_velocity = {};
  k.relative_angular_velocity = {};
  return law.evaluate(k, h.data());
}

template <class Law>
void expect_scaling_scales_the_load(const ContactLawSetting& setting) {
  const Law& law = std::get<Law>(setting.law);
  std::vector<double> h(Law::history_size, 0.0);
  const ContactForce before = loaded_bond(law, h, true);
  ASSERT_EQ(bond_state(h.data()), BondState::intact);  // elastic: the load is small against the strengths
  // One pair whose contact point is 0.6 m below a surface at z = 1 under
  // gamma = 1e4 N/m3: sigma_v = 6 kPa against a reference of 10 kPa.
  ReplicatedBody body;
  body.stride = Law::history_size;
  body.spheres = {{{0.0, 0.0, 0.4 - 1e-3}, 1e-3}, {{0.0, 0.0, 0.4 + 1e-3}, 1e-3}};
  body.id = {0, 1};
  body.pairs = {{0, 1}};
  body.rows = h;
  const StressProfile profile{.surface_z = 1.0, .unit_weight = 1e4, .k0 = 0.5, .surcharge = 0.0};
  const StressScalingReport report = scale_to_profile(body, setting.info->history, profile, 1e4);
  ASSERT_EQ(report.scaled_bonds, 1u);
  const double lambda = 0.6;
  EXPECT_DOUBLE_EQ(report.lambda_min, lambda);
  std::vector<double> scaled = body.rows;
  const ContactForce after = loaded_bond(law, scaled, false);
  // The scaled row is the state of the same bond under lambda times the load:
  // the law, asked again with no motion, returns lambda times the force and
  // couple (round-off of a few products: 1e-12 relative).
  EXPECT_LT(norm(after.on_first - lambda * before.on_first), 1e-12 * norm(before.on_first));
  EXPECT_LT(norm(after.couple_on_first - lambda * before.couple_on_first), 1e-12 * norm(before.couple_on_first));
  EXPECT_EQ(bond_state(scaled.data()), BondState::intact);
}

TEST(StressScaling, ScalingADamageBondsHistoryScalesItsForceAndCouple) {
  expect_scaling_scales_the_load<DamageBondLaw>(chalk());
}

TEST(StressScaling, ScalingASoftBondsHistoryScalesItsForceAndCouple) {
  // Zheng et al. (2023) Table 2 (docs/references.md).
  expect_scaling_scales_the_load<SoftBondLaw>(make_contact_law({{"law", "soft_bond"}, {"sb_emod_pa", 2.8e9}, {"kratio", 2.4}, {"sb_coh_pa", 4.5e5},
                                                                 {"sb_ten_pa", 4.5e5}, {"sb_fa_deg", 32}, {"sb_soft", 100}, {"sb_cut", 0.05}}));
}

TEST(StressScaling, LawsWithAnOverlapTermCannotBeScaled) {
  EXPECT_FALSE(test::linear(1e5, 5e4, 0.5, 0.2).intact_force_from_history());
  EXPECT_TRUE(chalk().intact_force_from_history());
}

}  // namespace
}  // namespace dfc::dem
