// The DEM section: errors name the key path (CONTRIBUTING.md §6).
#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/model_layout.hpp"

namespace dfc::dem {
namespace {

/// The ConfigError thrown for `config`, or a failure.
ConfigError error_of(const nlohmann::json& config) {
  try {
    (void)build_model(parse_dem_config(config));
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no ConfigError for " << config.dump();
  return ConfigError("", "");
}

TEST(DemConfig, TheTestBedIsValidAndUsesTheDefaults) {
  const DemConfig c = parse_dem_config(test::box_bed_config());
  EXPECT_EQ(c.walls.size(), 5u);
  EXPECT_EQ(lay_out_model(c).spheres.size(), 5u * 5u * 3u);
  EXPECT_EQ(std::get<LinearLaw>(c.walls[0].contact.law).friction, 0.5);  // wall_contact defaults to contact
  EXPECT_EQ(std::get<LinearLaw>(c.walls[1].contact.law).friction, 0.0);  // per-wall override
  EXPECT_EQ(c.timestep.fraction_of_critical, 0.3);
  EXPECT_EQ(c.local_damping, 0.7);
  EXPECT_EQ(c.threads, 0);
}

// timestep.stiffness_bound: per_particle unless the older bound is asked for;
// the model's step follows it (the bed's radii 4.5-5 mm: sqrt(5/4.5) apart,
// timestep.hpp); any other value is refused naming the key.
TEST(DemConfig, StiffnessBoundChoosesTheStepAndNamesItsKey) {
  nlohmann::json c = test::box_bed_config();
  c["contact"] = {{"law", "damage_bond"}, {"emod_pa", 1e8}, {"bond_emod_pa", 1e8}, {"ten_pa", 1e6}, {"com_pa", 1e7}, {"coh_pa", 1e6},
                  {"ucn_m", 1e-4}, {"ucs_m", 1e-4}, {"theta_c_rad", 0.01}};
  const DemModel per_particle = build_model(parse_dem_config(c));
  EXPECT_EQ(parse_dem_config(c).timestep.step_bound, StepBound::per_particle);
  c["timestep"]["stiffness_bound"] = "largest_radius";
  EXPECT_EQ(parse_dem_config(c).timestep.step_bound, StepBound::largest_radius);
  const DemModel largest = build_model(parse_dem_config(c));
  EXPECT_GT(per_particle.dt_critical, largest.dt_critical);
  EXPECT_NEAR(per_particle.simulation->critical_timestep(), per_particle.dt_critical, 1e-15);
  c["timestep"]["stiffness_bound"] = "smallest";
  EXPECT_EQ(error_of(c).key_path(), "timestep.stiffness_bound");
}

// Issue 20: 100000 threads passed `check` and crashed the server in libgomp;
// 4294967297 silently became 1.
TEST(DemConfig, ThreadCountIsBoundedAndNeverWraps) {
  nlohmann::json c = test::box_bed_config();
  for (const long long threads : {100'000LL, 4'294'967'297LL, -1LL}) {
    c["threads"] = threads;
    EXPECT_EQ(error_of(c).key_path(), "threads") << threads;
  }
  c["threads"] = 4;
  EXPECT_EQ(parse_dem_config(c).threads, 4);
}

// Issue 20: pile.sides 1e8 exhausted memory with a bare std::bad_alloc.
TEST(DemConfig, PileSidesAreBounded) {
  nlohmann::json c = test::box_bed_config();
  c["pile"] = {{"radius_m", 0.002}, {"tip_z_m", 0.05}, {"length_m", 0.02}, {"sides", 100'000'000}};
  EXPECT_EQ(error_of(c).key_path(), "pile.sides");
}

// pile.local_damping: the loading stage's alpha, in [0, 1) like damping.local.
TEST(DemConfig, PileLocalDampingOutsideZeroToOneNamesTheKey) {
  nlohmann::json c = test::box_bed_config();
  c["pile"] = {{"radius_m", 0.002}, {"tip_z_m", 0.05}, {"length_m", 0.02}};
  for (const double alpha : {1.0, -0.1, 1.5}) {
    c["pile"]["local_damping"] = alpha;
    EXPECT_EQ(error_of(c).key_path(), "pile.local_damping") << alpha;
  }
  c["pile"]["local_damping"] = 0.2;
  EXPECT_EQ(parse_dem_config(c).pile->local_damping, 0.2);
  c["pile"].erase("local_damping");
  EXPECT_FALSE(parse_dem_config(c).pile->local_damping.has_value());  // absent: damping.local throughout
}

TEST(DemConfig, UnknownContactLawNamesTheKeyAndListsTheRegistry) {
  nlohmann::json c = test::box_bed_config();
  c["contact"]["law"] = "hertz";
  const ConfigError e = error_of(c);
  EXPECT_EQ(e.key_path(), "contact.law");
  EXPECT_NE(e.reason().find("\"linear\""), std::string::npos) << e.what();
}

TEST(DemConfig, NegativeRadiusNamesTheKey) {
  nlohmann::json c = test::box_bed_config();
  c["particles"]["radius_min_m"] = -0.001;
  EXPECT_EQ(error_of(c).key_path(), "particles.radius_min_m");
}

TEST(DemConfig, UnknownKeysAreErrorsWithTheirPath) {
  nlohmann::json c = test::box_bed_config();
  c["contact"]["kn"] = 1e5;
  EXPECT_EQ(error_of(c).key_path(), "contact.kn");
  c = test::box_bed_config();
  c["walls"][2]["normall"] = {1, 0, 0};
  const ConfigError e = error_of(c);
  EXPECT_EQ(e.key_path(), "walls[2].normall");
  EXPECT_NE(e.reason().find("did you mean \"normal\""), std::string::npos) << e.what();
  c = test::box_bed_config();
  c["particles"]["region"]["radius_m"] = 0.1;  // not a key of a box
  EXPECT_EQ(error_of(c).key_path(), "particles.region.radius_m");
}

TEST(DemConfig, MissingStiffnessAndFixedStepAboveCriticalAreRefused) {
  nlohmann::json c = test::box_bed_config();
  c["contact"].erase("kn_n_m");
  EXPECT_EQ(error_of(c).key_path(), "contact.kn_n_m");
  c = test::box_bed_config();
  c["timestep"] = {{"dt_s", 1.0}};
  EXPECT_EQ(error_of(c).key_path(), "timestep.dt_s");
}

// Particle upscaling (docs/theory/upscaling_and_pcrm.md §2): radii x S and
// each law's declared rule. Exact equality: the rules are products by powers of
// S = 2, exact in binary floating point.
TEST(DemConfig, UpscalingScalesRadiiAndFollowsEachLawsRule) {
  nlohmann::json c = test::box_bed_config();
  c["particles"]["region"]["max_m"] = {0.12, 0.12, 0.07};  // room for the doubled spheres
  const DemConfig base = parse_dem_config(c);
  c["upscaling"] = {{"scale_factor", 2.0}};
  const DemConfig up = parse_dem_config(c);
  EXPECT_EQ(up.scale_factor, 2.0);
  EXPECT_EQ(up.particles.lattice.radius_min, 2.0 * base.particles.lattice.radius_min);
  EXPECT_EQ(up.particles.lattice.radius_max, 2.0 * base.particles.lattice.radius_max);
  for (const auto& s : lay_out_model(up).spheres) EXPECT_GE(s.radius, up.particles.lattice.radius_min);
  // linear: stiffness ~ E* R (exponent 1), friction and damping ratio fixed.
  const auto& law = std::get<LinearLaw>(up.contact.law);
  EXPECT_EQ(law.kn, 2.0 * std::get<LinearLaw>(base.contact.law).kn);
  EXPECT_EQ(law.friction, std::get<LinearLaw>(base.contact.law).friction);
  EXPECT_EQ(std::get<LinearLaw>(up.walls[1].contact.law).kn, 2.0 * std::get<LinearLaw>(base.walls[1].contact.law).kn);  // per-wall law too

  // soft_bond: moduli and strengths fixed, bonding gap x S.
  c["contact"] = {{"law", "soft_bond"}, {"sb_emod_pa", 2.8e9}, {"kratio", 2.4}, {"sb_ten_pa", 4.5e5}, {"sb_coh_pa", 4.5e5}, {"sb_fa_deg", 32},
                  {"sb_soft", 100},     {"sb_cut", 0.05},   {"bond_gap_m", 6e-5}};
  const DemConfig soft = parse_dem_config(c);
  EXPECT_EQ(soft.contact.bond_gap(), 1.2e-4);
  EXPECT_EQ(std::get<SoftBondLaw>(soft.contact.law).emod, 2.8e9);
  EXPECT_EQ(std::get<SoftBondLaw>(soft.contact.law).tensile_strength, 4.5e5);
}

TEST(DemConfig, UpscalingAListedPackingIsRefusedWithTheFix) {
  nlohmann::json c = test::box_bed_config();
  c["particles"] = {{"generator", "list"}, {"density_kg_m3", 2650}, {"spheres", {{0.01, 0.01, 0.01, 0.004}}}};
  c["upscaling"] = {{"scale_factor", 2.0}};
  const ConfigError e = error_of(c);
  EXPECT_EQ(e.key_path(), "particles.generator");
  EXPECT_NE(e.reason().find("scale_factor"), std::string::npos) << e.what();
  c["upscaling"] = {{"scale_factor", 0.0}};
  EXPECT_EQ(error_of(c).key_path(), "upscaling.scale_factor");
}

}  // namespace
}  // namespace dfc::dem
