// Golden-data tests of the bonded contact laws: one contact driven along
// loading paths (pure tension, shear and bending to failure, combined N–V–M,
// cyclic unload–reload, compression) and compared step by step with values
// computed independently from the equations by golden/bond_laws_golden.py
// (python3 + numpy; rerun it to regenerate golden/bond_laws.json).
//
// Reasoning per law (details in the script's docstring):
//  - linear_pbond: incremental N, F_s, M_t, M_b with k̄ A, k̄ I, k̄ J and the
//    peak stresses at the periphery (docs/theory/dem_contact_laws.md §2.3–2.5);
//  - soft_bond: the inferred softening form of docs/dem_bond_laws.md;
//  - damage_bond: uniaxial paths, where the return to the envelope is its
//    axis intercept, so N = σ_t A exp(-(u - u_t)/u_cn) in tension etc. in
//    closed form (dem_contact_laws.md §3.2–3.4), and the breakage at D > 0.99.
// Tolerance: the C++ and Python sums of the same increments round
// differently by a few ulps per step (<= 1300 steps), and the damage_bond
// return stops within f in [-1e-12, 0] of the surface, i.e. ~1e-12 relative
// per yielding step, accumulated in the plastic displacements: 1e-8 of the
// largest value of a series covers both. Bond states must match exactly
// (the paths avoid landing exactly on a strength).
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/damage_envelope.hpp"

namespace dfc::dem {
namespace {

const nlohmann::json& golden() {
  static const nlohmann::json data = [] {
    std::ifstream in(std::string(DFC_DEM_GOLDEN_DIR) + "/bond_laws.json");
    return nlohmann::json::parse(in);
  }();
  return data;
}

const nlohmann::json& golden_case(const std::string& name) {
  for (const auto& c : golden()["cases"])
    if (c["name"] == name) return c;
  throw std::runtime_error("no golden case " + name);
}

/// Drives one contact of `case_` and compares every step.
void replay(const std::string& name) {
  const nlohmann::json& c = golden_case(name);
  nlohmann::json object = c["parameters"];
  object["law"] = c["law"];
  const ContactLawSetting setting = make_contact_law(object);
  std::vector<double> history(setting.history_size(), 0.0);
  set_bond_state(history.data(), BondState::intact);
  const double dt = golden()["dt_s"], r = golden()["radius_m"];
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = c["overlap"];
  k.effective_mass = 1e-6;
  k.radius_first = k.radius_second = r;
  k.dt = dt;

  const auto& expected = c["expected"];
  double scale[4] = {0, 0, 0, 0};
  for (const auto& row : expected)
    for (int q = 0; q < 4; ++q) scale[q] = std::max(scale[q], std::abs(row[q].get<double>()));
  std::size_t step = 0;
  for (const auto& ph : c["phases"]) {
    k.relative_velocity = {ph["dus"].get<double>() / dt, 0.0, ph["dun"].get<double>() / dt};
    k.relative_angular_velocity = {ph["dtb"].get<double>() / dt, 0.0, ph["dtt"].get<double>() / dt};
    for (int s = 0; s < ph["steps"].get<int>(); ++s, ++step) {
      const ContactForce f = std::visit([&](const auto& law) { return law.evaluate(k, history.data()); }, setting.law);
      const auto& e = expected[step];
      const double got[4] = {f.on_first.x, f.on_first.z, f.couple_on_first.x, f.couple_on_first.z};
      for (int q = 0; q < 4; ++q) ASSERT_NEAR(got[q], e[q].get<double>(), 1e-8 * scale[q] + 1e-300) << name << " step " << step << " quantity " << q;
      ASSERT_EQ(int(bond_state(history.data())), e[4].get<int>()) << name << " step " << step;
      if (e.size() > 5) {
        ASSERT_NEAR(history[DamageBondLaw::damage], e[5].get<double>(), 1e-8) << name << " step " << step;
      }
      // Nothing is transmitted sideways: the paths load x and z only.
      ASSERT_EQ(f.on_first.y, 0.0);
    }
  }
}

TEST(LinearPbondGolden, PureTensionBreaksInTensionAtTheTensileStrength) { replay("pbond_tension_to_failure"); }
TEST(LinearPbondGolden, PureShearBreaksInShearAtTheCohesion) { replay("pbond_shear_to_failure"); }
TEST(LinearPbondGolden, BendingBreaksInTensionAtThePeripheryStress) { replay("pbond_bending_to_failure"); }
TEST(LinearPbondGolden, CombinedNvmWithTheLinearPartInParallel) { replay("pbond_combined_nvm_with_linear_part"); }
TEST(LinearPbondGolden, CyclicUnloadReloadIsElastic) { replay("pbond_cyclic_unload_reload"); }

TEST(SoftBondGolden, TensionSoftensLinearlyThenBreaksAtTheCutStrength) { replay("soft_tension_softening_to_failure"); }
TEST(SoftBondGolden, CyclicUnloadReloadReturnsToTheSofteningLine) { replay("soft_cyclic_unload_reload"); }
TEST(SoftBondGolden, ShearIsBrittleThenTheLinearContactAlone) { replay("soft_shear_brittle"); }
TEST(SoftBondGolden, BendingSoftensThroughThePeripheralElongation) { replay("soft_bending_softening"); }
TEST(SoftBondGolden, CompressionRaisesTheShearStrength) { replay("soft_combined_compression_shear_twist"); }

TEST(DamageBondGolden, TensionDecaysExponentiallyAndBreaksAboveD099) { replay("damage_tension_to_failure"); }
TEST(DamageBondGolden, CompressionYieldsAtTheCompressiveStrength) { replay("damage_compression"); }
TEST(DamageBondGolden, ShearDecaysExponentiallyAndBreaks) { replay("damage_shear_to_failure"); }
TEST(DamageBondGolden, BendingDecaysExponentiallyAndBreaks) { replay("damage_bending_to_failure"); }
TEST(DamageBondGolden, CyclicTensionUnloadsWithTheDamagedStiffness) { replay("damage_cyclic_tension"); }

TEST(DamageEnvelope, ClosestPointMatchesABruteForceSearch) {
  const auto& g = golden()["damage_nv_return"];
  const EnvelopePoint t{g["trial"][0], g["trial"][1], g["trial"][2]};
  const ReturnWeights w{g["weights"][0], g["weights"][1], g["weights"][2]};
  const EnvelopePoint x = closest_admissible_point(t, w);
  // The golden-section search converges to ~1e-12; the C++ return stops
  // within f in [-1e-12, 0] of the surface.
  EXPECT_NEAR(x.n, g["expected"][0].get<double>(), 1e-7);
  EXPECT_NEAR(x.v, g["expected"][1].get<double>(), 1e-7);
  EXPECT_EQ(x.m, 0.0);
  EXPECT_LE(damage_envelope(x), 0.0);
}

}  // namespace
}  // namespace dfc::dem
