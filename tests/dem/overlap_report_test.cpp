// The overlap guard's message names the contact that broke it
// (Simulation::describe_largest_overlap, contacts/overlap_report.cpp): a run
// that stops on it after hours must say where, between which particles, and
// whether their bond was intact, for the user to choose the remedy; the limit
// is the scenario's timestep.max_overlap_fraction.
#include <string>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/model_builder.hpp"

namespace dfc::dem {
namespace {

std::string failure_message(const nlohmann::json& config) {
  DemModel model = build_model(parse_dem_config(config));
  try {
    model.simulation->step(model.dt, ContactRecord::complete);
  } catch (const SolverError& e) {
    return e.what();
  }
  return "";
}

TEST(OverlapReport, NamesThePairWithTheLargestOverlapRelativeToTheSmallerRadius) {
  const double r = 1e-3;
  // Pair 0-1 overlaps by 0.3 r (under the guard); pair 2-3 by 0.3 r against a
  // radius of r/2: 0.6 of the smaller radius, the one the guard fires on.
  const nlohmann::json config = {
      {"particles",
       {{"generator", "list"},
        {"spheres", {{0.0, 0.0, 0.0, r}, {1.7 * r, 0.0, 0.0, r}, {0.0, 0.0, 10 * r, r}, {1.2 * r, 0.0, 10 * r, 0.5 * r}}},
        {"density_kg_m3", 2650}}},
      {"contact", {{"law", "linear"}, {"kn_n_m", 1e5}, {"ks_n_m", 5e4}}},
  };
  const std::string message = failure_message(config);
  ASSERT_FALSE(message.empty()) << "the guard did not fire";
  EXPECT_NE(message.find("the pair of particle id 2"), std::string::npos) << message;
  EXPECT_NE(message.find("and particle id 3"), std::string::npos) << message;
  EXPECT_NE(message.find("= 0.6 of the smaller radius"), std::string::npos) << message;
  EXPECT_NE(message.find("at step 0"), std::string::npos) << message;
}

TEST(OverlapReport, TheLimitIsTimestepMaxOverlapFraction) {
  const double r = 1e-3;
  // One pair at 0.6 of the smaller radius (as above).
  nlohmann::json config = {
      {"particles", {{"generator", "list"}, {"spheres", {{0.0, 0.0, 0.0, r}, {1.2 * r, 0.0, 0.0, 0.5 * r}}}, {"density_kg_m3", 2650}}},
      {"contact", {{"law", "linear"}, {"kn_n_m", 1e5}, {"ks_n_m", 5e4}}},
  };
  EXPECT_NE(failure_message(config).find("exceeded 0.5 of the smaller particle radius"), std::string::npos) << "the default limit is 0.5";
  config["timestep"] = {{"max_overlap_fraction", 0.65}};
  EXPECT_EQ(failure_message(config), "") << "0.6 is under a limit of 0.65";
  config["timestep"] = {{"max_overlap_fraction", 0.55}};
  EXPECT_NE(failure_message(config).find("exceeded 0.55 of the smaller particle radius"), std::string::npos);
}

TEST(OverlapReport, NamesTheWall) {
  const double r = 1e-3;
  // The builder removes spheres that start in a wall: the sphere starts
  // clear of the floor and is then moved into it by `depth`.
  const nlohmann::json config = {
      {"particles", {{"generator", "list"}, {"spheres", {{0.0, 0.0, 2.0 * r, r}}}, {"density_kg_m3", 2650}}},
      {"contact", {{"law", "linear"}, {"kn_n_m", 1e5}, {"ks_n_m", 5e4}}},
      {"walls", {{{"type", "plane"}, {"name", "floor"}, {"point_m", {0, 0, 0}}, {"normal", {0, 0, 1}}}}},
  };
  const auto failure_at_depth = [&](double depth) -> std::string {
    DemModel model = build_model(parse_dem_config(config));
    model.simulation->particles_for_edit().position[0].z = r - depth;
    model.simulation->request_rebuild();
    try {
      model.simulation->step(model.dt, ContactRecord::complete);
    } catch (const SolverError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(failure_at_depth(0.3 * r), "") << "an overlap of 0.3 r is under the guard";
  const std::string message = failure_at_depth(0.6 * r);
  EXPECT_NE(message.find("wall 'floor' and particle id 0"), std::string::npos) << message;
  EXPECT_NE(message.find("= 0.6 of its radius"), std::string::npos) << message;
}

}  // namespace
}  // namespace dfc::dem
