// Which listed spheres the model builder keeps next to a wall: one that
// overlaps it by at most 1e-3 of its radius rests on it (a contact, as in a
// packing settled against that wall, e.g. the peer benchmark's); one deeper
// in is cut by it and removed (it would start with a large overlap).
#include <gtest/gtest.h>

#include <fstream>

#include "dem_test_support.hpp"

namespace dfc::dem {
namespace {

TEST(ModelBuilder, KeepsSpheresRestingOnAWallAndRemovesThoseItCuts) {
  const double r = 1e-3;
  // Floor at z = 0; centres at r (touching), r (1 - 5e-4) and r (1 - 2e-3),
  // far enough apart in x not to touch each other.
  const nlohmann::json config = {
      {"particles",
       {{"generator", "list"},
        {"spheres", {{0.0, 0.0, r, r}, {0.01, 0.0, r * (1.0 - 5e-4), r}, {0.02, 0.0, r * (1.0 - 2e-3), r}}},
        {"density_kg_m3", 2650}}},
      {"contact", {{"law", "linear"}, {"kn_n_m", 1e5}, {"ks_n_m", 5e4}}},
      {"walls", {{{"type", "plane"}, {"name", "floor"}, {"point_m", {0.01, 0.0, 0.0}}, {"normal", {0, 0, 1}}}}},
  };
  const DemModel model = build_model(parse_dem_config(config));
  EXPECT_EQ(model.removed_particles, 1u);
  ASSERT_EQ(model.simulation->particles().size(), 2u);
  // The kept ones are the first two, at their listed heights.
  EXPECT_EQ(model.simulation->particles().position[0].z, r);
  EXPECT_EQ(model.simulation->particles().position[1].z, r * (1.0 - 5e-4));
}

// A generated body is copied into the simulation; the model keeps its report
// but not its arrays. The paper model's generated rows (0.45 GB) used to stay
// allocated for the whole run: `v = {}` empties a vector but keeps its storage.
TEST(ModelBuilder, AGeneratedBodyLeavesNoArraysBehind) {
  std::ifstream in(DFC_E2E_SCENARIOS_DIR "/centrifuge_generation_small.json");
  ASSERT_TRUE(in) << "the e2e scenario the section is taken from";
  const nlohmann::json scenario = nlohmann::json::parse(in);
  nlohmann::json section = scenario["participants"]["dem"]["config"];
  section["gravity_m_s2"] = {0.0, 0.0, -9.81 * 100};  // as the coupler adds it (g_level 100)
  const DemModel model = build_model(parse_dem_config(section));
  ASSERT_TRUE(model.generation);
  ASSERT_GT(model.simulation->particles().size(), 1000u);  // a body with arrays worth releasing
  const ReplicatedBody& body = model.generation->body;
  EXPECT_EQ(body.id.capacity(), 0u);
  EXPECT_EQ(body.spheres.capacity(), 0u);
  EXPECT_EQ(body.material.capacity(), 0u);
  EXPECT_EQ(body.pairs.capacity(), 0u);
  EXPECT_EQ(body.rows.capacity(), 0u);
}

}  // namespace
}  // namespace dfc::dem
