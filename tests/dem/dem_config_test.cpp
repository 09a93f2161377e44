// The DEM section: errors name the key path (DESIGN §7, STYLE 6).
#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/dem/dem_config.hpp"

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
  EXPECT_EQ(c.particles.spheres.size(), 5u * 5u * 3u);
  EXPECT_EQ(std::get<LinearLaw>(c.walls[0].contact.law).friction, 0.5);  // wall_contact defaults to contact
  EXPECT_EQ(std::get<LinearLaw>(c.walls[1].contact.law).friction, 0.0);  // per-wall override
  EXPECT_EQ(c.timestep.fraction_of_critical, 0.3);
  EXPECT_EQ(c.local_damping, 0.7);
  EXPECT_EQ(c.threads, 0);
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

}  // namespace
}  // namespace dfc::dem
