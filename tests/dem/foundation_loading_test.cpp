// The pile as a foundation (foundation_loading.hpp): it starts only when the
// DEM is in equilibrium, and its force splits exactly into tip and shaft.
#include <gtest/gtest.h>

#include "dfc/dem/dem_backend.hpp"
#include "dfc/dem/foundation_loading.hpp"
#include "dfc/dem/wall_builders.hpp"
#include "dem_test_support.hpp"

namespace dfc::dem {
namespace {

/// The free-falling bed of dem_test_support.hpp on a floor.
nlohmann::json falling_bed() {
  nlohmann::json config = test::cylinder_bed_under_gravity();
  config["walls"] = {{{"type", "plane"}, {"point_m", {0, 0, 0}}, {"normal", {0, 0, 1}}}};
  return config;
}

protocol::AdvanceRequest steps(std::int64_t n, double dt) {
  protocol::AdvanceRequest r;
  r.n_steps = n;
  r.dt = dt;
  return r;
}

TEST(FoundationLoading, TheTipIsTheFlatEndThatLeadsTheMotion) {
  const Wall pile = make_wall("pile", make_closed_cylinder_mesh({.tip_z = 0.01, .radius = 0.005, .length = 0.05, .sides = 24}),
                              WallMotion::prescribed, {});
  const std::vector<std::size_t> down = pile_tip_facets(pile, {0, 0, -2});
  ASSERT_EQ(down.size(), 24u);  // one triangle per side of the 24-gon
  for (const std::size_t f : down)
    for (const std::uint32_t v : pile.facets[f]) EXPECT_EQ(pile.vertices[v].z, 0.01);
  EXPECT_EQ(pile_tip_facets(pile, {0, 0, 1}).size(), 24u);  // pulled up: the top leads
  EXPECT_TRUE(pile_tip_facets(pile, {1, 0, 0}).empty());     // no side facet faces exactly along x
}

TEST(FoundationLoading, APileWaitingForEquilibriumRestsWhileTheBedFalls) {
  // A lattice bed released under gravity is far from equilibrium (its
  // unbalanced-force ratio is about 1 in free fall): a pile that waits for a
  // ratio of 1e-9 must not move, whatever its start_step.
  nlohmann::json config = falling_bed();
  config["pile"] = {{"radius_m", 0.005}, {"tip_z_m", 0.04}, {"length_m", 0.05}, {"velocity_m_s", {0, 0, -0.5}},
                    {"start_when", {{"unbalanced_force_ratio", 1e-9}}}};
  DemBackend backend;
  const double dt = backend.configure(config)["dt_suggested"];
  for (int k = 0; k < 5; ++k) EXPECT_EQ(backend.advance(steps(20, dt)).monitors["pile_displacement_m"].get<double>(), 0.0);
}

TEST(FoundationLoading, APileWhoseRuleIsMetStartsAtTheNextStepAfterItsStartStep) {
  // A ratio of 1 is met at every exchange: the pile starts at the first
  // exchange end at or after start_step 30, i.e. after the second advance of 20.
  nlohmann::json config = falling_bed();
  config["pile"] = {{"radius_m", 0.005}, {"tip_z_m", 0.04}, {"length_m", 0.05}, {"velocity_m_s", {0, 0, -0.5}}, {"start_step", 30},
                    {"start_when", {{"unbalanced_force_ratio", 1.0}}}};
  DemBackend backend;
  const double dt = backend.configure(config)["dt_suggested"];
  EXPECT_EQ(backend.advance(steps(20, dt)).monitors["pile_displacement_m"].get<double>(), 0.0);
  EXPECT_EQ(backend.advance(steps(20, dt)).monitors["pile_displacement_m"].get<double>(), 0.0);
  EXPECT_NEAR(backend.advance(steps(20, dt)).monitors["pile_displacement_m"].get<double>(), 20 * dt * 0.5, 1e-15);
}

TEST(FoundationLoading, TipAndShaftForcesAddUpToThePileForce) {
  // The pile stands in the bed (spheres inside it are removed) and is pushed
  // down into it while the bed falls around it: the tip carries load, and tip
  // and shaft sum to the total (the same contacts grouped by facet: equal to rounding).
  nlohmann::json config = falling_bed();
  config["pile"] = {{"radius_m", 0.008}, {"tip_z_m", 0.009}, {"length_m", 0.05}, {"velocity_m_s", {0, 0, -0.5}}};
  DemBackend backend;
  const double dt = backend.configure(config)["dt_suggested"];
  const nlohmann::json m = backend.advance(steps(700, dt)).monitors;
  const double total = m["pile_force_n"], tip = m["pile_tip_force_n"], shaft = m["pile_shaft_force_n"];
  EXPECT_GT(std::abs(total), 0.0);
  EXPECT_NEAR(tip + shaft, total, 1e-12 * std::abs(total));
  EXPECT_GT(tip, 0.0);  // the spheres below resist the tip
}

}  // namespace
}  // namespace dfc::dem
