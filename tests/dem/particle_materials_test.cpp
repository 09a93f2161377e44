// Particle materials (particle_materials.hpp): the mixing rule of a pair of
// materials, the pair laws of a simulation with several materials, and the
// bonding of the seams between them.
#include <cmath>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/particle_materials.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {
namespace {

ContactLawSetting chalk() {
  // Ciantia et al. (2024) Table 1 (docs/references.md) at S = 1.
  return make_contact_law({{"law", "damage_bond"}, {"emod_pa", 1.7e9}, {"kratio", 5}, {"friction", 0.5}, {"bond_emod_pa", 1.7e9},
                           {"bond_kratio", 5}, {"ten_pa", 1e6}, {"com_pa", 5e7}, {"coh_pa", 2e6}, {"ucn_m", 2e-5}, {"ucs_m", 2e-5},
                           {"theta_c_rad", 0.006}, {"bond_gap_m", 2.62e-5}});
}

TEST(ParticleMaterials, TwoUpscalingsOfOneSetMixToTheSetAtTheirGeometricMeanScale) {
  // The graded chalk of Ciantia et al. (2024): S = 2.1 next to S = 4.8. The
  // mixed set is the set upscaled by sqrt(2.1 x 4.8) (u_cn, u_cs and the bond
  // gap scale with S; the rest is equal). Tolerance: a square root and a
  // power of the same numbers, a few ulps.
  const ContactLawSetting base = chalk();
  const ContactLawSetting mixed = mix_contact_laws(upscale(base, 2.1), upscale(base, 4.8));
  const ContactLawSetting expected = upscale(base, std::sqrt(2.1 * 4.8));
  ASSERT_EQ(mixed.values.size(), expected.values.size());
  for (std::size_t k = 0; k < mixed.values.size(); ++k)
    EXPECT_NEAR(mixed.values[k], expected.values[k], 1e-14 * std::abs(expected.values[k])) << base.info->parameters[k].key;
  EXPECT_NEAR(std::get<DamageBondLaw>(mixed.law).u_cn, 2e-5 * std::sqrt(2.1 * 4.8), 1e-19);
}

TEST(ParticleMaterials, AParameterThatDoesNotScaleMixesByItsMean) {
  ContactLawSetting a = test::linear(1e5, 5e4, 0.2), b = test::linear(1e5, 5e4, 0.6);
  const ContactLawSetting mixed = mix_contact_laws(a, b);
  EXPECT_DOUBLE_EQ(std::get<LinearLaw>(mixed.law).friction, 0.4);
  EXPECT_EQ(std::get<LinearLaw>(mixed.law).kn, 1e5);  // equal values stay exactly equal
}

TEST(ParticleMaterials, AMaterialWithItselfKeepsItsSetBitForBit) {
  const ContactLawSetting a = upscale(chalk(), 3.3);
  const ParticleMaterials materials({a, upscale(chalk(), 4.8)});
  EXPECT_EQ(materials.pair_setting(materials.pair_index(0, 0)).values, a.values);
  EXPECT_EQ(materials.pair_setting(materials.pair_index(0, 1)).values, materials.pair_setting(materials.pair_index(1, 0)).values);
}

TEST(ParticleMaterials, MaterialsOfDifferentLawsAreRefused) {
  EXPECT_THROW(ParticleMaterials({chalk(), test::linear(1e5, 5e4)}), UserError);
}

/// Two spheres of radius 1 mm, `overlap` apart from touching, of materials a and b.
Simulation pair_of(const ContactLawSetting& m0, const ContactLawSetting& m1, MaterialId a, MaterialId b, double overlap) {
  Simulation sim(SimulationSettings{.particle_law = m0, .gravity = {}, .local_damping = 0.0, .skin = 0.0, .threads = 1, .install_bonds_at_start = true,
                                    .material_laws = {m1}});
  sim.add_sphere(0, {0.0, 0.0, 0.0}, 1e-3, 2650, a);
  sim.add_sphere(1, {2e-3 - overlap, 0.0, 0.0}, 1e-3, 2650, b);
  return sim;
}

TEST(ParticleMaterials, EachPairActsWithTheLawOfItsTwoMaterials) {
  // linear law: k_n of material 1 is 4x material 0's (S = 4 on k ~ S), so a
  // pair 0-0 carries k_n0 delta, 1-1 4 k_n0 delta and 0-1 the geometric mean,
  // 2 k_n0 delta (the law at S = 2). Tolerance: delta is a difference of
  // millimetre coordinates, so it carries about 1e-16 x 2e-3 / 1e-6 = 2e-13
  // relative round-off.
  const ContactLawSetting soft = test::linear(1e5, 5e4, 0.5), stiff = upscale(soft, 4.0);
  const double delta = 1e-6;
  const auto normal_force = [&](MaterialId a, MaterialId b) {
    Simulation sim = pair_of(soft, stiff, a, b, delta);
    sim.step(1e-7);
    return std::abs(sim.contact_outputs().force[0].x);
  };
  EXPECT_NEAR(normal_force(0, 0), 1e5 * delta, 1e-11 * 1e5 * delta);
  EXPECT_NEAR(normal_force(1, 1), 4e5 * delta, 1e-11 * 4e5 * delta);
  EXPECT_NEAR(normal_force(0, 1), 2e5 * delta, 1e-11 * 2e5 * delta);
  EXPECT_NEAR(normal_force(1, 0), 2e5 * delta, 1e-11 * 2e5 * delta);
}

TEST(ParticleMaterials, AnUnknownMaterialIsRefused) {
  Simulation sim(SimulationSettings{.particle_law = chalk(), .gravity = {}, .local_damping = 0.7, .skin = 0.0, .threads = 1});
  EXPECT_THROW(sim.add_sphere(0, {}, 1e-3, 2650, 1), UserError);
}

TEST(ParticleMaterials, BondingAcrossMaterialsBondsOnlyTheUnlikePairs) {
  // A row of three touching spheres, materials 0, 0, 1, nothing bonded at
  // start: only the 0-1 pair is a seam, so exactly one bond forms, between
  // spheres 1 and 2, and with zero load (no force after one step at rest).
  const ContactLawSetting fine = upscale(chalk(), 2.0), coarse = upscale(chalk(), 4.0);
  Simulation sim(SimulationSettings{.particle_law = fine, .gravity = {}, .local_damping = 0.7, .skin = 0.0, .threads = 1,
                                    .install_bonds_at_start = false, .material_laws = {coarse}});
  for (int k = 0; k < 3; ++k) sim.add_sphere(k, {2e-3 * k, 0.0, 0.0}, 1e-3, 2650, k == 2 ? 1 : 0);
  sim.bond_across_materials_now();
  sim.step(1e-9);
  EXPECT_EQ(sim.bond_counts().intact, 1);
  const PairContacts& pairs = sim.pair_contacts();
  const ParticleStore& p = sim.particles();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const bool unlike = p.material[pairs.first[k]] != p.material[pairs.second[k]];
    EXPECT_EQ(bond_state(pairs.history.data() + k * pairs.stride) == BondState::intact, unlike);
    EXPECT_LT(norm(sim.contact_outputs().force[k]), 1e-12);
  }
}

}  // namespace
}  // namespace dfc::dem
