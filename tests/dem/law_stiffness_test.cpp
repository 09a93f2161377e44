// Which stiffness each law's modulus key sets (docs/dem_bond_laws.md, table
// "What each modulus sets"): the registry states it per key
// (ContactLawInfo::stiffness, printed by dem_server --help), and here each
// statement is checked against the force the law returns, in closed form.
//
// One pair for every case: unequal spheres R1 = 1 mm, R2 = 2.5 mm, so that
// R_min (1 mm) and R1 + R2 (3.5 mm) differ and a formula that used the wrong
// one would miss by a factor 3.5 or more. A bonded law's spring is read from
// one step: the linear contact from an overlap δ (F = k_n δ), the bond from an
// opening v_n dt across a gap (N = k̄_n A v_n dt). Every expected value is a
// product and quotient of a few doubles, as is the law's: 1e-14 relative
// leaves room for the different order of the roundings (about 1e-16 each).
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"
#include "dfc/dem/contact_law_registry.hpp"

namespace dfc::dem {
namespace {

constexpr double r1 = 1e-3, r2 = 2.5e-3;  // m
constexpr double r_min = r1, r_sum = r1 + r2;
constexpr double modulus = 2.8e9;         // Pa, every E* and Ē* below
constexpr double overlap = 1e-8;          // m
constexpr double opening_rate = 1e-3;     // m/s
constexpr double dt = 1e-6;               // s
constexpr double relative = 1e-14;
constexpr double strong = 1e12;           // Pa, strengths no step here reaches

ContactKinematics pair(double gap_overlap, double normal_velocity) {
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = gap_overlap;
  k.relative_velocity = {0.0, 0.0, normal_velocity};
  k.effective_mass = 1e-5;
  k.radius_first = r1;
  k.radius_second = r2;
  k.dt = dt;
  return k;
}

/// The normal stiffness the law shows: from an overlap with the bond in
/// `state` (the linear or unbonded contact), F_n / δ.
template <class Law>
double contact_stiffness(const nlohmann::json& parameters, BondState state) {
  const Law law = std::get<Law>(make_contact_law(parameters).law);
  std::vector<double> history(Law::history_size, 0.0);
  set_bond_state(history.data(), state);
  return -law.evaluate(pair(overlap, 0.0), history.data()).on_first.z / overlap;
}

/// The bond's normal stiffness k̄_n A the law shows: N / (v_n dt) after one
/// step of opening across a gap with the bond intact.
template <class Law>
double bond_stiffness(const nlohmann::json& parameters) {
  const Law law = std::get<Law>(make_contact_law(parameters).law);
  std::vector<double> history(Law::history_size, 0.0);
  set_bond_state(history.data(), BondState::intact);
  return law.evaluate(pair(-1e-7, opening_rate), history.data()).on_first.z / (opening_rate * dt);
}

/// The registry's statement for `key` of `law`, or "" if it has none.
std::string stated(std::string_view law, std::string_view key) {
  for (const auto& meaning : find_contact_law(law)->stiffness)
    if (meaning.key == key) return meaning.formula;
  return "";
}

// k_n of the PFC deformability method, Potyondy & Cundall (2004), Itasca PFC
// linear model (docs/theory/dem_contact_laws.md §2.2): a bar of section π R_min² and length R1 + R2.
double linear_contact_kn() { return std::numbers::pi * modulus * r_min * r_min / r_sum; }
// Stiffness per area of a bond disc, §2.2, over the disc A = π (λ R_min)².
double bond_kn_times_area(double lambda) { return modulus / r_sum * std::numbers::pi * (lambda * r_min) * (lambda * r_min); }

TEST(LawStiffness, EveryModulusAndStiffnessKeyStatesWhatItSets) {
  for (const auto& law : contact_law_registry()) {
    for (const auto& p : law.parameters) {
      const bool sets_stiffness = p.key.ends_with("emod_pa") || p.key == "kn_n_m" || p.key == "ks_n_m";
      if (!sets_stiffness) continue;
      bool found = false;
      for (const auto& meaning : law.stiffness) found = found || meaning.key == p.key;
      EXPECT_TRUE(found) << law.keyword << "." << p.key << " has no stiffness statement in the registry";
    }
    for (const auto& meaning : law.stiffness) {
      bool declared = false;
      for (const auto& p : law.parameters) declared = declared || p.key == meaning.key;
      EXPECT_TRUE(declared) << law.keyword << ": the statement names " << meaning.key << ", which the law does not read";
      EXPECT_FALSE(meaning.source.empty()) << law.keyword << "." << meaning.key;
    }
  }
}

TEST(LawStiffness, LinearKnIsTheGivenStiffnessWhateverTheRadii) {
  EXPECT_EQ(stated("linear", "kn_n_m"), "k_n = kn_n_m [N/m], the same for every pair");
  const double kn = 3e5;
  const double measured = contact_stiffness<LinearLaw>({{"law", "linear"}, {"kn_n_m", kn}, {"ks_n_m", kn}}, BondState::none);
  EXPECT_NEAR(measured, kn, relative * kn);
}

TEST(LawStiffness, LinearPbondEmodSetsTheLinearContactOnTheSectionOfRmin) {
  EXPECT_EQ(stated("linear_pbond", "emod_pa"), "k_n = pi E* R_min^2/(R1+R2) [N/m], k_s = k_n/kratio");
  // pb_rmul 0.6 must not enter the linear part.
  const nlohmann::json p{{"law", "linear_pbond"}, {"emod_pa", modulus}, {"pb_emod_pa", 1.0}, {"pb_rmul", 0.6},
                         {"pb_ten_pa", strong}, {"pb_coh_pa", strong}};
  EXPECT_NEAR(contact_stiffness<LinearPbondLaw>(p, BondState::none), linear_contact_kn(), relative * linear_contact_kn());
}

TEST(LawStiffness, LinearPbondBondEmodSetsStiffnessPerAreaOfTheBondDisc) {
  EXPECT_EQ(stated("linear_pbond", "pb_emod_pa"), "kbar_n = Ebar*/(R1+R2) [Pa/m] on the disc A = pi (pb_rmul R_min)^2, kbar_s = kbar_n/pb_kratio");
  const double lambda = 0.6;
  const nlohmann::json p{{"law", "linear_pbond"}, {"emod_pa", 1.0}, {"pb_emod_pa", modulus}, {"pb_rmul", lambda},
                         {"pb_ten_pa", strong}, {"pb_coh_pa", strong}};
  EXPECT_NEAR(bond_stiffness<LinearPbondLaw>(p), bond_kn_times_area(lambda), relative * bond_kn_times_area(lambda));
}

TEST(LawStiffness, SoftBondModulusSetsTheBondDiscBondedAndUnbonded) {
  EXPECT_EQ(stated("soft_bond", "sb_emod_pa"),
            "k_n = E*/(R1+R2) [Pa/m] on the disc A = pi (sb_rmul R_min)^2, k_s = k_n/kratio, bonded and unbonded (k_n A [N/m] after breakage)");
  const double lambda = 0.6;
  const nlohmann::json p{{"law", "soft_bond"}, {"sb_emod_pa", modulus}, {"sb_rmul", lambda}, {"sb_ten_pa", strong}, {"sb_coh_pa", strong}};
  const double expected = bond_kn_times_area(lambda);
  EXPECT_NEAR(bond_stiffness<SoftBondLaw>(p), expected, relative * expected);
  // After breakage the same springs, as a no-tension contact: λ² times the
  // linear_pbond contact of the same modulus, which is why the key has its own name.
  EXPECT_NEAR(contact_stiffness<SoftBondLaw>(p, BondState::broken_tension), expected, relative * expected);
  EXPECT_NEAR(expected / linear_contact_kn(), lambda * lambda, 1e-15);
}

TEST(LawStiffness, DamageBondEmodSetsTheLinearContactAndBondEmodTheDisc) {
  EXPECT_EQ(stated("damage_bond", "emod_pa"), "k_n = pi E* R_min^2/(R1+R2) [N/m], k_s = k_n/kratio, once the bond is damaged or broken");
  EXPECT_EQ(stated("damage_bond", "bond_emod_pa"),
            "kbar_n = Ebar*/(R1+R2) [Pa/m] on the disc A = pi (bond_rmul R_min)^2, kbar_s = kbar_n/bond_kratio, times (1 - D)");
  const double lambda = 0.6;
  const auto parameters = [&](double emod, double bond_emod) {
    return nlohmann::json{{"law", "damage_bond"}, {"emod_pa", emod}, {"bond_emod_pa", bond_emod}, {"bond_rmul", lambda},
                          {"ten_pa", strong}, {"com_pa", strong}, {"coh_pa", strong}, {"ucn_m", 1.0}, {"ucs_m", 1.0}, {"theta_c_rad", 1.0}};
  };
  EXPECT_NEAR(contact_stiffness<DamageBondLaw>(parameters(modulus, 1.0), BondState::broken_shear), linear_contact_kn(),
              relative * linear_contact_kn());
  EXPECT_NEAR(bond_stiffness<DamageBondLaw>(parameters(1.0, modulus)), bond_kn_times_area(lambda), relative * bond_kn_times_area(lambda));
}

// emod_pa means the linear contact's modulus wherever it is read; soft_bond's
// modulus, which sets the bond disc, was once read under that name. A scenario
// still using it must not run with a silently different stiffness: it is
// refused, naming the key path and the new key.
TEST(LawStiffness, SoftBondRefusesTheOldModulusKeyNamingTheNewOne) {
  try {
    (void)make_contact_law({{"law", "soft_bond"}, {"emod_pa", modulus}, {"sb_ten_pa", 1e6}, {"sb_coh_pa", 1e6}});
    FAIL() << "emod_pa was accepted by soft_bond";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("contact.emod_pa"), std::string::npos) << what;
    EXPECT_NE(what.find("sb_emod_pa"), std::string::npos) << what;
  }
}

TEST(LawStiffness, HelpPrintsEveryStatement) {
  const std::string help = describe_contact_laws();
  for (const auto& law : contact_law_registry())
    for (const auto& meaning : law.stiffness) EXPECT_NE(help.find(meaning.formula), std::string::npos) << law.keyword << "." << meaning.key;
  EXPECT_NE(help.find("emod_pa: renamed sb_emod_pa"), std::string::npos);
}

}  // namespace
}  // namespace dfc::dem
