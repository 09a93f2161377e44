// The fdm_server section: errors name the key path (CONTRIBUTING.md §6).
#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/fdm_config.hpp"
#include "dfc/constitutive/structured_cam_clay_model.hpp"

namespace dfc::fdm {
namespace {

nlohmann::json valid_section() {
  return nlohmann::json::parse(R"({
    "mesh": {"type": "box", "size_m": [1, 1, 2], "zones": [2, 2, 4]},
    "material": {"model": "elastic", "density_kg_m3": 2000, "young_modulus_pa": 1e7, "poisson_ratio": 0.3},
    "gravity_m_s2": [0, 0, -9.81],
    "damping": {"local": 0.8},
    "mass_scaling": true,
    "threads": 1,
    "boundaries": [{"group": "zmin", "condition": "fixed"}, {"group": "xmin", "condition": "roller"},
                   {"group": "zmax", "condition": "pressure", "pressure_pa": 1000}],
    "initial_stress": {"type": "geostatic", "k0": 0.5},
    "coupling": {"role": "provider", "group": "zmax"}
  })");
}

std::string key_path_of_error(const nlohmann::json& section) {
  try {
    (void)load_fdm_model(section);
  } catch (const ConfigError& e) {
    return e.key_path();
  }
  return "<no error>";
}

TEST(FdmConfig, ValidSectionBuildsTheModel) {
  const FdmModel model = load_fdm_model(valid_section());
  EXPECT_EQ(model.solver.mesh().gridpoint_count(), 3u * 3u * 5u);
  EXPECT_EQ(model.coupling.role, CouplingRole::provider);
  EXPECT_EQ(model.coupling.group, "zmax");
  EXPECT_DOUBLE_EQ(model.solver.settings().gravity.z(), -9.81);
  // Geostatic: the top zones are near zero stress, the bottom ones compressed.
  EXPECT_LT(model.solver.zone_stress(0).zz, -1000.0);
}

// Issue 20: 4294967297 threads wrapped to 1 before the 1024 check saw it.
TEST(FdmConfig, ThreadCountIsBoundedAndNeverWraps) {
  nlohmann::json section = valid_section();
  for (const long long threads : {100'000LL, 4'294'967'297LL, -1LL}) {
    section["threads"] = threads;
    EXPECT_EQ(key_path_of_error(section), "threads") << threads;
  }
}

TEST(FdmConfig, UnknownKeyIsNamed) {
  nlohmann::json section = valid_section();
  section["gravty_m_s2"] = {0, 0, -9.81};
  EXPECT_EQ(key_path_of_error(section), "gravty_m_s2");
  section = valid_section();
  section["mesh"]["zonez"] = 3;
  EXPECT_EQ(key_path_of_error(section), "mesh.zonez");
  section = valid_section();
  section["boundaries"][1]["pressure_pa"] = 5;  // only for pressure conditions
  EXPECT_EQ(key_path_of_error(section), "boundaries[1].pressure_pa");
}

TEST(FdmConfig, NegativeSizeIsNamed) {
  nlohmann::json section = valid_section();
  section["mesh"]["size_m"] = {1, -1, 2};
  EXPECT_EQ(key_path_of_error(section), "mesh.size_m[1]");  // the element, as the schema names it
  section = valid_section();
  section["mesh"]["zones"] = {2, 0, 4};
  EXPECT_EQ(key_path_of_error(section), "mesh.zones[1]");
  section["mesh"] = {{"type", "cylinder_cavity"}, {"inner_radius_m", 2.0}, {"outer_radius_m", 1.0}, {"height_m", 1.0}};
  EXPECT_EQ(key_path_of_error(section), "mesh.outer_radius_m");
}

TEST(FdmConfig, BadCavityFloorsAreNamed) {
  nlohmann::json section = valid_section();
  section["coupling"]["group"] = "inner";
  section["boundaries"] = nlohmann::json::parse(R"([{"group": "bottom", "condition": "fixed"}])");
  section["mesh"] = nlohmann::json::parse(R"({"type": "cylinder_cavity", "inner_radius_m": 0.5, "outer_radius_m": 2, "height_m": 2,
                                              "zones_radial": 2, "zones_around": 16, "zones_vertical": 4, "cavity_floor_z_m": 1})");
  EXPECT_EQ(key_path_of_error(section), "<no error>");
  for (const double outside : {2.0, -1.0, 3.0}) {
    section["mesh"]["cavity_floor_z_m"] = outside;
    EXPECT_EQ(key_path_of_error(section), "mesh.cavity_floor_z_m") << outside;
  }
  // At z_bottom_m (the default) the floor is no floor: the annulus as without the key.
  section["mesh"]["cavity_floor_z_m"] = 0.0;
  const std::size_t annulus = load_fdm_model(section).solver.mesh().gridpoint_count();
  section["mesh"].erase("cavity_floor_z_m");
  EXPECT_EQ(load_fdm_model(section).solver.mesh().gridpoint_count(), annulus);
  section["mesh"]["cavity_floor_z_m"] = 1.0;
  EXPECT_GT(load_fdm_model(section).solver.mesh().gridpoint_count(), annulus);
  section["mesh"]["cavity_floor_z_m"] = 0.7;  // between the levels 0.5 and 1.0
  EXPECT_EQ(key_path_of_error(section), "mesh.cavity_floor_z_m");
  section["mesh"]["cavity_floor_z_m"] = 1.5;
  section["mesh"]["zones_around"] = 18;
  EXPECT_EQ(key_path_of_error(section), "mesh.zones_around");
  section["mesh"]["zones_around"] = 16;
  section["mesh"]["angle_deg"] = 90;
  EXPECT_EQ(key_path_of_error(section), "mesh.angle_deg");
}

TEST(FdmConfig, UnknownModelIsNamed) {
  nlohmann::json section = valid_section();
  section["material"]["model"] = "mohr_coulomb_typo";
  try {
    (void)load_fdm_model(section);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key_path(), "material.model");
    EXPECT_NE(e.reason().find("\"elastic\""), std::string::npos) << "the error should list the known models: " << e.reason();
  }
}

TEST(FdmConfig, BadMaterialAndGroupValuesAreNamed) {
  nlohmann::json section = valid_section();
  section["material"]["poisson_ratio"] = 0.5;
  EXPECT_EQ(key_path_of_error(section), "material.poisson_ratio");
  section = valid_section();
  section["material"]["bulk_modulus_pa"] = 1e7;  // together with E/nu: ambiguous
  EXPECT_EQ(key_path_of_error(section), "material.bulk_modulus_pa");
  section = valid_section();
  section["boundaries"][0]["group"] = "bottom";
  EXPECT_EQ(key_path_of_error(section), "boundaries[0].group");
  section = valid_section();
  section["coupling"]["role"] = "leader";
  EXPECT_EQ(key_path_of_error(section), "coupling.role");
  section = valid_section();
  section["damping"]["local"] = 1.0;
  EXPECT_EQ(key_path_of_error(section), "damping.local");
  section = valid_section();
  section["gravity_m_s2"] = {1.0, 0.0, -9.81};  // geostatic needs gravity along −z
  EXPECT_EQ(key_path_of_error(section), "initial_stress.type");
}

TEST(FdmConfig, RollerOnCylinderWallIsRadialAndAccepted) {
  nlohmann::json section = valid_section();
  section["mesh"] = nlohmann::json::parse(
      R"({"type": "cylinder_cavity", "inner_radius_m": 0.5, "outer_radius_m": 2, "height_m": 1,
          "zones_radial": 3, "zones_around": 12, "zones_vertical": 2, "grading_ratio": 1.2})");
  section["boundaries"] = nlohmann::json::parse(R"([{"group": "outer", "condition": "roller"}, {"group": "bottom", "condition": "fixed"}])");
  section["coupling"]["group"] = "inner";
  EXPECT_NO_THROW((void)load_fdm_model(section));
}

TEST(FdmConfig, HelpListsModelsWithParametersAndUnits) {
  const std::string help = fdm_config_help();
  for (const char* expected : {"\"elastic\"", "young_modulus_pa [Pa]", "poisson_ratio [-]", "bulk_modulus_pa [Pa]", "shear_modulus_pa [Pa]",
                               "cylinder_cavity", "grading_ratio", "mass_scaling", "initial_stress", "coupling", "\"mohr_coulomb\"",
                               "cohesion_pa [Pa]", "friction_angle_deg [deg]", "dilation_angle_deg [deg]", "tensile_strength_pa [Pa]",
                               "\"structured_cam_clay\"", "ps0_pa [Pa]", "pt0_pa [Pa]", "mf [-]", "mg [-]", "rho_s [-]", "rho_t [-]",
                               "xi_s [-]", "xi_t [-]", "\"chalk_snw\"", "sphere_cavity_octant", "angle_deg", "max_aspect_ratio", "preset"})
    EXPECT_NE(help.find(expected), std::string::npos) << expected;
}

TEST(FdmConfig, ChalkPresetIsSeedTable2AndKeysNextToItOverride) {
  nlohmann::json section = valid_section();
  section["material"] = {{"preset", "chalk_snw"}, {"density_kg_m3", 1900.0}};
  const FdmModel model = load_fdm_model(section);
  const auto* cam_clay = dynamic_cast<const constitutive::StructuredCamClayModel*>(&model.solver.model());
  ASSERT_NE(cam_clay, nullptr);
  const constitutive::StructuredCamClayParameters& m = cam_clay->parameters();
  EXPECT_DOUBLE_EQ(m.ps0, 3.0e6);
  EXPECT_DOUBLE_EQ(m.pt0, 2.0e5);
  EXPECT_DOUBLE_EQ(m.mf, 1.0);
  EXPECT_DOUBLE_EQ(m.mg, 1.2);
  EXPECT_DOUBLE_EQ(m.rho_s, 19.0);
  EXPECT_DOUBLE_EQ(m.rho_t, 15.0);
  EXPECT_DOUBLE_EQ(m.xi_s, 0.5);
  EXPECT_DOUBLE_EQ(m.xi_t, 0.5);
  EXPECT_NEAR(9.0 * m.moduli.bulk * m.moduli.shear / (3.0 * m.moduli.bulk + m.moduli.shear), 1.0e9, 1e-3);  // E = 1 GPa
  EXPECT_DOUBLE_EQ(model.solver.density(), 1900.0);  // the override
  section["material"] = {{"preset", "chalk_snv"}};
  EXPECT_EQ(key_path_of_error(section), "material.preset");
  section["material"] = {{"preset", "chalk_snw"}, {"rho_tt", 3.0}};
  EXPECT_EQ(key_path_of_error(section), "material.rho_tt");
}

TEST(FdmConfig, PlasticModelParametersAreValidatedWithTheirKeyPaths) {
  nlohmann::json section = valid_section();
  section["material"] = nlohmann::json::parse(R"({"model": "mohr_coulomb", "density_kg_m3": 2000, "young_modulus_pa": 1e8,
      "poisson_ratio": 0.25, "cohesion_pa": 1e4, "friction_angle_deg": 30, "dilation_angle_deg": 10, "tensile_strength_pa": 0})");
  EXPECT_NO_THROW((void)load_fdm_model(section));
  section["material"]["dilation_angle_deg"] = 35;
  EXPECT_EQ(key_path_of_error(section), "material.dilation_angle_deg");
  section["material"]["dilation_angle_deg"] = 0;
  section["material"].erase("tensile_strength_pa");
  EXPECT_EQ(key_path_of_error(section), "material.tensile_strength_pa");
  section["material"] = {{"preset", "chalk_snw"}, {"mf", -1.0}};
  EXPECT_EQ(key_path_of_error(section), "material.mf");
}

TEST(FdmConfig, SectorAndSphereOctantMeshesAreAccepted) {
  nlohmann::json section = valid_section();
  section["initial_stress"] = nullptr;
  section["gravity_m_s2"] = {0.0, 0.0, 0.0};
  section["mesh"] = nlohmann::json::parse(R"({"type": "cylinder_cavity", "inner_radius_m": 1, "outer_radius_m": 2, "height_m": 0.2,
      "zones_radial": 4, "zones_around": 6, "zones_vertical": 1, "angle_deg": 90})");
  section["boundaries"] = nlohmann::json::parse(R"([{"group": "theta_min", "condition": "roller"}, {"group": "theta_max", "condition": "roller"}])");
  section["coupling"]["group"] = "inner";
  EXPECT_NO_THROW((void)load_fdm_model(section));
  section["mesh"] = nlohmann::json::parse(R"({"type": "sphere_cavity_octant", "inner_radius_m": 1, "outer_radius_m": 2,
      "zones_radial": 4, "zones_around": 3})");
  section["boundaries"] = nlohmann::json::parse(R"([{"group": "xmin", "condition": "roller"}, {"group": "zmin", "condition": "roller"}])");
  EXPECT_NO_THROW((void)load_fdm_model(section));
  section["mesh"]["grading_ratio"] = 3.0;  // innermost zones: Δr = 0.025 m against 0.26 m around
  EXPECT_EQ(key_path_of_error(section), "mesh.max_aspect_ratio");
}

}  // namespace
}  // namespace dfc::fdm
