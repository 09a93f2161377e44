// Periodic cell replication (pcrm_replication.hpp) and stress scaling
// (stress_scaling.hpp) on a small bonded REV of the chalk law of Ciantia et al. (2024).
#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/pcrm_zones.hpp"
#include "dfc/dem/rev_preparation.hpp"
#include "dfc/dem/stress_scaling.hpp"

namespace dfc::dem {
namespace {

SimulationSettings settings() {
  return SimulationSettings{.particle_law = test::chalk_at_s10(), .gravity = {}, .local_damping = 0.7, .skin = 0.0, .threads = 1};
}

/// About 250 spheres of the chalk PSD at S = 10 in an 8 mm cell, at sigma_ref
/// (Pa) on z and K0 = 0.5.
PreparedRev chalk_rev(double sigma_ref) {
  RevSpec spec;
  spec.particles = {.radius_min = 3.275e-4, .radius_max = 9.025e-4, .porosity = 0.45, .multiplier = 1.6, .stages = 10, .relax_steps = 300, .seed = 5};
  spec.cell = {.lo = {}, .hi = {8e-3, 8e-3, 8e-3}, .periodic = {true, true, true}, .strain_rate = {}};
  spec.density = 2556;
  spec.consolidation.tolerance = 0.02;
  spec.consolidation.unbalanced_force_ratio = 0.05;
  spec.consolidation.loading = {.mode = CellLoading::Mode::anisotropic, .axis = 2, .stress = sigma_ref, .lateral_ratio = 0.5, .axial_rate = 0.0, .strain_rate = {}};
  spec.fraction_of_critical = 0.3;
  return prepare_rev(spec, settings(), "particles.rev");
}

/// The REV at 100 kPa.
const PreparedRev& rev() {
  static const PreparedRev prepared = chalk_rev(1e5);
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

TEST(Pcrm, TheRevIsTheSameStateScaledAtAnyReferenceStress) {
  // 300 Pa: about the mid-depth sigma_v of the small chalk model (32 mm deep)
  // at 1.4 g; 100 kPa: at 450 g. The unbonded packing is consolidated at the
  // installation stress whatever sigma_ref, and the bonds are installed at
  // rest with zero load (rev_preparation.hpp), so the bonded stage loads an
  // elastic network from zero: while no bond yields its state is linear in
  // the load (damage_bond_law.hpp, Eq. 1) and the servo, whose step is the
  // stress error over the network's stiffness (cell_servo.hpp), takes the
  // same steps whatever the target. Before, stage 2 ran at the mean of
  // sigma_ref: at the stress of 10 g it did not converge in 200 000 steps.
  const PreparedRev low = chalk_rev(300.0);
  const PreparedRev& high = rev();
  EXPECT_NEAR(low.stress.z, 300.0, 0.02 * 300.0);  // the servo's tolerance
  EXPECT_NEAR(low.stress.x, 150.0, 0.02 * 150.0);
  EXPECT_NEAR(low.stress.y, 150.0, 0.02 * 150.0);
  EXPECT_EQ(low.damaged_bonds, 0);  // nothing locked in by the installation
  // The same packing, its porosity apart by the bonded stage's elastic
  // volumetric strain, about 2 sigma_ref / E = 1.2e-4 at 100 kPa (measured on
  // the body: 3e-5 between 220 Pa and 44 kPa), and the same bonds.
  EXPECT_NEAR(low.porosity, high.porosity, 3e-4);
  EXPECT_EQ(low.bonds + low.damaged_bonds, high.bonds + high.damaged_bonds);
  // Steps: the same count but for the last check interval (100 steps) of the bonded stage.
  EXPECT_NEAR(double(low.steps), double(high.steps), 0.02 * double(high.steps));
}

TEST(Pcrm, ABodyReleasedIntoItsArchiveGivesTheArchiveItWouldCopy) {
  // The model builder moves the generated rows into the simulation's seed
  // (release_into_archive) instead of copying them (archive): the same keys
  // and rows, all-zero rows dropped as add() drops them, and nothing left in
  // the body.
  const PreparedRev& r = rev();
  const Vec3 l = r.cell.length();
  ReplicatedBody body = replicate(r, {.shape = BedRegion::Shape::box, .min = r.cell.lo, .max = r.cell.lo + 2.0 * l}, 1.0, true);
  // A fresh (all-zero) row among the bonds, which neither archive keeps.
  ASSERT_GT(body.pairs.size(), 2u);
  std::fill_n(body.rows.begin() + std::ptrdiff_t(body.stride), body.stride, 0.0);
  const HistoryArchive copied = body.archive();
  const HistoryArchive taken = body.release_into_archive();
  ASSERT_EQ(taken.size(), copied.size());
  EXPECT_EQ(taken.size() + 1, std::size_t(8 * r.bonds));  // every bond but the zeroed row
  for (std::size_t k = 0; k < copied.size(); ++k) {
    ASSERT_EQ(taken.key(k), copied.key(k));
    EXPECT_TRUE(std::equal(copied.row(k), copied.row(k) + copied.stride(), taken.row(k)));
    EXPECT_EQ(taken.find(copied.key(k)), taken.row(k));
  }
  EXPECT_EQ(body.id.capacity() + body.spheres.capacity() + body.material.capacity() + body.pairs.capacity() + body.rows.capacity(), 0u);
}

TEST(Pcrm, ARegionOfWholeCellsIsCoveredByThatManyCopiesDespiteRoundOff) {
  // (lo + 2 l) - lo is 2 l only to round-off; a third copy would tile a
  // periodic body wrongly (seen: a REV whose deformed cell gave 3 x 3 x 2).
  int above = 0;
  for (int k = 0; k < 2000; ++k) {
    const double l = 8e-3 * (1.0 + 1e-7 * k), lo = 1e-3 * (1.0 + 3e-7 * k);
    const Vec3 edge{l, l, l}, low{lo, -lo, 0.0};
    const Vec3 high = low + 2.0 * edge;
    above += (high.x - low.x) / l > 2.0 || (high.y - low.y) / l > 2.0 ? 1 : 0;
    const auto copies = copies_to_cover(edge, low, high);
    ASSERT_EQ(copies[0], 2) << "k = " << k;
    ASSERT_EQ(copies[1], 2) << "k = " << k;
    ASSERT_EQ(copies[2], 2) << "k = " << k;
  }
  EXPECT_GT(above, 0);  // the round-off that the rule must absorb occurs
  EXPECT_EQ(copies_to_cover({1, 1, 1}, {0, 0, 0}, {2.001, 1, 0.5})[0], 3);  // a real part of a copy still counts
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
  expect_scaling_scales_the_load<DamageBondLaw>(test::chalk_at_s10());
}

TEST(StressScaling, ScalingASoftBondsHistoryScalesItsForceAndCouple) {
  // Zheng et al. (2023) Table 2 (docs/references.md).
  expect_scaling_scales_the_load<SoftBondLaw>(make_contact_law({{"law", "soft_bond"}, {"sb_emod_pa", 2.8e9}, {"kratio", 2.4}, {"sb_coh_pa", 4.5e5},
                                                                 {"sb_ten_pa", 4.5e5}, {"sb_fa_deg", 32}, {"sb_soft", 100}, {"sb_cut", 0.05}}));
}

TEST(StressScaling, LawsWithAnOverlapTermCannotBeScaled) {
  EXPECT_FALSE(test::linear(1e5, 5e4, 0.5, 0.2).intact_force_from_history());
  EXPECT_TRUE(test::chalk_at_s10().intact_force_from_history());
}

}  // namespace
}  // namespace dfc::dem

namespace dfc::dem {
namespace {

/// A damage bond between two spheres of radius r, moved by `v` per step of 1 us
/// for `steps` steps (v = 0: evaluated at rest).
ContactForce moved_bond(const DamageBondLaw& law, std::vector<double>& h, double r, const Vec3& v, int steps) {
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.radius_first = k.radius_second = r;
  k.effective_mass = 1e-6;
  k.dt = 1e-6;
  k.relative_velocity = v;
  ContactForce f{};
  for (int s = 0; s < steps; ++s) f = law.evaluate(k, h.data());
  return f;
}

TEST(PcrmZones, TheRevScaledToAnotherSIsTheSameStateAtAnotherSize) {
  // A zone of S_k is filled with the REV (prepared at S_0) scaled by
  // s = S_k / S_0 (pcrm_zones.hpp): lengths x s, each history column x s^e by
  // its unit. With the law upscaled to S_k (u_cn, u_cs x s; moduli and
  // strengths fixed) a damaged, yielding bond must then carry s^2 times the
  // force and s^3 times the couple, at the same damage: the same stresses.
  const double s0 = 2.1, s = 4.8 / 2.1, r = 0.116e-3 * s0 / 2.0;
  // Copies: upscale() returns a temporary, and a reference into its law
  // dangled from the end of this statement (AddressSanitizer: stack-use-after-scope).
  const DamageBondLaw law0 = std::get<DamageBondLaw>(upscale(test::chalk_at_s10(), s0).law);
  const DamageBondLaw law1 = std::get<DamageBondLaw>(upscale(test::chalk_at_s10(), s0 * s).law);
  std::vector<double> h(DamageBondLaw::history_size, 0.0);
  set_bond_state(h.data(), BondState::intact);
  // Shear and a little opening at 1 cm/s until the bond has yielded and lost 5 % or more of its stiffness.
  for (int block = 0; block < 200 && h[DamageBondLaw::damage] < 0.05; ++block) (void)moved_bond(law0, h, r, {1e-2, 0.0, 1e-3}, 50);
  ASSERT_GT(h[DamageBondLaw::damage], 0.05);
  ASSERT_EQ(bond_state(h.data()), BondState::damaged);
  std::vector<double> before_row = h;
  const ContactForce before = moved_bond(law0, before_row, r, {}, 1);

  PreparedRev one;
  one.stride = DamageBondLaw::history_size;
  one.spheres = {{{0.0, 0.0, 0.0}, r}, {{0.0, 0.0, 2.0 * r}, r}};
  one.pairs = {RevPair{0, 1, {0, 0, 0}}};
  one.rows = h;
  one.cell = {.lo = {}, .hi = {4.0 * r, 4.0 * r, 4.0 * r}, .periodic = {true, true, true}, .strain_rate = {}};
  const PreparedRev scaled = scaled_rev(one, s, upscale(test::chalk_at_s10(), s0).info->history);
  EXPECT_DOUBLE_EQ(scaled.spheres[1].centre.z, 2.0 * r * s);
  EXPECT_DOUBLE_EQ(scaled.cell.hi.x, 4.0 * r * s);
  std::vector<double> after_row = scaled.rows;
  const ContactForce after = moved_bond(law1, after_row, r * s, {}, 1);
  // Tolerance: the law's products in another order of magnitude, 1e-12 relative.
  EXPECT_LT(norm(after.on_first - s * s * before.on_first), 1e-12 * s * s * norm(before.on_first));
  EXPECT_LT(norm(after.couple_on_first - s * s * s * before.couple_on_first), 1e-12 * s * s * s * norm(before.couple_on_first) + 1e-30);
  EXPECT_NEAR(after_row[DamageBondLaw::damage], before_row[DamageBondLaw::damage], 1e-12);
}

TEST(PcrmZones, EachZoneIsFilledAtItsScaleAndTheSeamsOverlapLittle) {
  // The REV (S = 10, 8 mm cell) fills x < 16 mm of a 48 x 16 x 16 mm box; the
  // same REV at S = 20 fills the rest. The fine zone yields at the seam.
  const PreparedRev& r = rev();
  const BedRegion body_region{.shape = BedRegion::Shape::box, .min = {}, .max = {48e-3, 16e-3, 16e-3}};
  const BedRegion fine_region{.shape = BedRegion::Shape::box, .min = {}, .max = {16e-3, 16e-3, 16e-3}};
  const std::vector<PcrmZone> zones{{10.0, fine_region}, {20.0, std::nullopt}};
  const double seam = 0.1;
  const ZonedBody zoned = replicate_zones(r, test::chalk_at_s10().info->history, body_region, zones, 0.0, seam);
  const ReplicatedBody& b = zoned.body;
  ASSERT_EQ(zoned.zone_spheres.size(), 2u);
  EXPECT_EQ(zoned.zone_spheres[0] + zoned.zone_spheres[1], b.spheres.size());
  EXPECT_GT(zoned.zone_spheres[0], 6 * r.spheres.size());   // 8 copies, less those cut by the box
  EXPECT_GT(zoned.zone_spheres[1], r.spheres.size());       // 2 copies of 8x the volume, less the cut ones
  double r_min = 1.0, r_max = 0.0;
  for (const auto& s : r.spheres) r_min = std::min(r_min, s.radius), r_max = std::max(r_max, s.radius);
  for (std::size_t i = 0; i < b.spheres.size(); ++i) {
    const GeneratedSphere& s = b.spheres[i];
    if (b.material[i] == 0) {
      EXPECT_LE(s.centre.x, 16e-3 + s.radius);  // a fine sphere seated on the coarse zone moves by at most its radius
      EXPECT_GE(s.radius, r_min);
      EXPECT_LE(s.radius, r_max);
    } else {
      EXPECT_GT(s.centre.x, 16e-3);
      EXPECT_GE(s.radius, 2.0 * r_min);
      EXPECT_LE(s.radius, 2.0 * r_max);
    }
    EXPECT_GE(clearance(s, body_region), 0.0);  // whole spheres (protrusion 0)
  }
  // No sphere overlaps one of the other zone by more than the seam fraction,
  // and the seated seam is a contact layer: coarse spheres touch fine ones
  // (to round-off), instead of standing up to a fine sphere off them.
  EXPECT_GT(zoned.seam_seated, 0u);
  std::size_t seam_pairs = 0;
  for (std::size_t i = 0; i < b.spheres.size(); ++i)
    for (std::size_t j = 0; j < b.spheres.size(); ++j) {
      if (b.material[i] != 0 || b.material[j] != 1) continue;
      const double overlap = b.spheres[i].radius + b.spheres[j].radius - norm(b.spheres[i].centre - b.spheres[j].centre);
      EXPECT_LE(overlap, seam * std::min(b.spheres[i].radius, b.spheres[j].radius));
      seam_pairs += overlap > -1e-9 * b.spheres[i].radius;
    }
  EXPECT_GE(seam_pairs, zoned.seam_seated);
  // Every pair of the body joins spheres of one zone, and a coarse pair's row
  // is an REV row scaled by 2 (exactly: a power of 2) by its columns' units.
  const auto& columns = test::chalk_at_s10().info->history;
  std::size_t coarse_pairs = 0;
  for (std::size_t k = 0; k < b.pairs.size(); ++k) {
    const auto [i, j] = b.pairs[k];
    ASSERT_EQ(b.material[i], b.material[j]);
    if (b.material[i] == 0) continue;
    ++coarse_pairs;
    const double* row = b.rows.data() + k * b.stride;
    bool found = false;
    for (std::size_t q = 0; q < r.pairs.size() && !found; ++q) {
      const double* rev_row = r.rows.data() + q * r.stride;
      bool same = true;
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const double factor = columns[c].unit == "N" ? 4.0 : columns[c].unit == "N m" ? 8.0 : columns[c].unit == "m" ? 2.0 : 1.0;
        same = same && row[c] == factor * rev_row[c];
      }
      found = same;
    }
    EXPECT_TRUE(found) << "pair " << k;
  }
  EXPECT_GT(coarse_pairs, r.pairs.size() / 2);  // two copies of the REV less what the box trims
}

}  // namespace
}  // namespace dfc::dem
