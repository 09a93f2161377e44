// UCS platens: signs of the stress–strain measures and the "ucs" section.
#include <gtest/gtest.h>

#include <numbers>

#include "dem_test_support.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/dem/dem_backend.hpp"
#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/model_layout.hpp"
#include "dfc/dem/ucs_platens.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

// Platens 0.02 m apart along +z; the particles push the top up and the bottom
// down with 10 N each: compression, σ = 10 N / 1e-4 m2 = 1e5 Pa.
TEST(UcsPlatens, CompressionIsPositiveInStressAndStrain) {
  const WallMesh top = make_plane_mesh({0, 0, 0.02}, {0, 0, -1}, 0.01);
  const WallMesh bottom = make_plane_mesh({0, 0, 0}, {0, 0, 1}, 0.01);
  const PlatenAxis a = platen_axis(top.vertices, bottom.vertices);
  EXPECT_NEAR(a.axis.z, 1.0, 1e-15);
  EXPECT_NEAR(a.initial_height, 0.02, 1e-15);
  EXPECT_NEAR(axial_stress(a, {0, 0, 10}, {0, 0, -10}, 1e-4), 1e5, 1e-9);
  EXPECT_NEAR(axial_stress(a, {0, 0, -10}, {0, 0, 10}, 1e-4), -1e5, 1e-9);  // tension reads negative
  // Unequal platen forces (inertia): the mean of the two.
  EXPECT_NEAR(axial_stress(a, {0, 0, 12}, {0, 0, -8}, 1e-4), 1e5, 1e-9);
  std::vector<Vec3> moved = top.vertices;
  for (auto& v : moved) v.z -= 0.0002;
  EXPECT_NEAR(axial_strain(a, platen_separation(a, moved, bottom.vertices)), 0.01, 1e-12);
}

nlohmann::json ucs_config() { return test::ucs_box_bed_config(); }

// Seating puts each platen on the outermost particle surface; the strain rate
// sets each platen moving at rate H0/2 towards the other, so dH/dt = -rate H0.
TEST(UcsPlatens, SectionSeatsThePlatensAndDrivesThemAtTheStrainRate) {
  const DemConfig c = parse_dem_config(ucs_config());
  ASSERT_TRUE(c.ucs.has_value());
  const ModelLayout layout = lay_out_model(c);
  double high = -1e9, low = 1e9;
  for (const auto& s : layout.spheres) {
    high = std::max(high, s.centre.z + s.radius);
    low = std::min(low, s.centre.z - s.radius);
  }
  const WallConfig& top = layout.walls[c.ucs->top_wall];
  const WallConfig& bottom = layout.walls[c.ucs->bottom_wall];
  EXPECT_NEAR(vertex_centroid(top.mesh.vertices).z, high, 1e-12);
  EXPECT_NEAR(vertex_centroid(bottom.mesh.vertices).z, low, 1e-12);
  const double h0 = high - low;
  EXPECT_NEAR(top.velocity.z, -0.5 * 2.0 * h0, 1e-12);
  EXPECT_NEAR(bottom.velocity.z, 0.5 * 2.0 * h0, 1e-12);
  EXPECT_NEAR(top.velocity.x, 0.0, 1e-15);
}

// Without area_m2 the cross-section of a box bed is the x–y bounding box of
// its spheres (ucs_loading.cpp): the advance-averaged axial_stress_pa equals
// ((F_top - F_bottom) . z) / (2 A) from the averaged platen forces with that A.
TEST(UcsPlatens, DerivedAreaTurnsThePlatenForcesIntoTheAxialStress) {
  const nlohmann::json config = ucs_config();
  double lo_x = 1e9, lo_y = 1e9, hi_x = -1e9, hi_y = -1e9;
  for (const auto& s : lay_out_model(parse_dem_config(config)).spheres) {
    lo_x = std::min(lo_x, s.centre.x - s.radius);
    lo_y = std::min(lo_y, s.centre.y - s.radius);
    hi_x = std::max(hi_x, s.centre.x + s.radius);
    hi_y = std::max(hi_y, s.centre.y + s.radius);
  }
  const double area = (hi_x - lo_x) * (hi_y - lo_y);
  DemBackend backend;
  const double dt = backend.configure(config)["dt_suggested"].get<double>();
  nlohmann::json m;
  for (int k = 0; k < 20; ++k) m = backend.advance({backend.simulation().step_count(), 50, dt, {}}).monitors;
  const double top = m["wall_top_force_n"][2].get<double>(), bottom = m["wall_bottom_force_n"][2].get<double>();
  ASSERT_GT(top - bottom, 0.0);  // the closing platens load the bed
  // The two sides differ only by the order of the same products (round-off).
  EXPECT_NEAR(m["axial_stress_pa"].get<double>(), (top - bottom) / (2.0 * area), 1e-12 * (top - bottom) / area);
}

TEST(UcsPlatens, SectionErrorsNameTheKey) {
  auto expect_key = [](const nlohmann::json& config, const std::string& key) {
    try {
      (void)parse_dem_config(config);
      ADD_FAILURE() << "no ConfigError for " << key;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.key_path(), key) << e.what();
    }
  };
  nlohmann::json c = ucs_config();
  c["ucs"]["top_wall"] = "lid";
  expect_key(c, "ucs.top_wall");
  c = ucs_config();
  c["ucs"]["bottom_wall"] = "top";
  expect_key(c, "ucs.bottom_wall");
  c = ucs_config();
  c["walls"][1]["velocity_m_s"] = {0, 0, -0.1};
  expect_key(c, "ucs.strain_rate_per_s");
  c = ucs_config();
  c["particles"] = {{"generator", "list"}, {"density_kg_m3", 2650}, {"spheres", {{0, 0, 0.1, 0.01}}}};
  expect_key(c, "ucs.area_m2");
}

}  // namespace
}  // namespace dfc::dem
