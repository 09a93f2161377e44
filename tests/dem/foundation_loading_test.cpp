// The pile as a foundation (foundation_loading.hpp): it starts only when the
// DEM is in equilibrium, and its force splits exactly into tip and shaft.
#include <gtest/gtest.h>

#include <cmath>

#include "dfc/dem/dem_backend.hpp"
#include "dfc/dem/foundation_loading.hpp"
#include "dfc/dem/pile_plug.hpp"
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

TEST(FoundationLoading, AnOpenTubeSplitsIntoAnnulusInnerAndOuterShaft) {
  // Ciantia et al. (2024) §3: D = 8 mm, wall 1 mm. 2 triangles per side for
  // each part; the annulus lies in the tip plane between the two radii, the
  // inner shaft's vertices on the bore's circle, the outer's on the outer circle.
  const CylinderGeometry g{.tip_z = 0.02, .radius = 0.004, .length = 0.03, .sides = 16, .inner_radius = 0.003};
  const Wall pile = make_wall("pile", make_pile_mesh(g), WallMotion::prescribed, {});
  ASSERT_EQ(pile.facet_count(), 6u * 16u);
  const std::vector<std::size_t> tip = pile_tip_facets(pile, {0, 0, -1});
  const std::vector<std::size_t> inner = pile_inner_facets(pile, 0.0, 0.0);
  const std::vector<std::size_t> outer = other_facets(pile, tip, inner);
  ASSERT_EQ(tip.size(), 32u);
  ASSERT_EQ(inner.size(), 32u);
  ASSERT_EQ(outer.size(), 32u);
  EXPECT_EQ(tip.front(), 0u);  // the annulus first: it owns both rims (wall_contacts.hpp ties)
  for (const std::size_t f : tip)
    for (const std::uint32_t v : pile.facets[f]) EXPECT_EQ(pile.vertices[v].z, 0.02);
  const auto radius_of = [&](std::uint32_t v) { return std::hypot(pile.vertices[v].x, pile.vertices[v].y); };
  for (const std::size_t f : inner)
    for (const std::uint32_t v : pile.facets[f]) EXPECT_NEAR(radius_of(v), 0.003, 1e-15);
  for (const std::size_t f : outer)
    for (const std::uint32_t v : pile.facets[f]) EXPECT_NEAR(radius_of(v), 0.004, 1e-15);
  // A closed pile has no inner shaft.
  const Wall closed = make_wall("pile", make_pile_mesh({.radius = 0.004, .length = 0.03}), WallMotion::prescribed, {});
  EXPECT_TRUE(pile_inner_facets(closed, 0.0, 0.0).empty());
}

TEST(FoundationLoading, AnOpenTubeCarriesSoilInItsBoreAndSplitsItsForceExactly) {
  // The tube (r 8 mm, wall 2 mm) is pushed into the falling bed from its
  // middle: the spheres in its bore stay (inside_pile removes only those in
  // its wall), and annulus + inner + outer = the total (the same contacts grouped by facet).
  nlohmann::json config = falling_bed();
  config["pile"] = {{"radius_m", 0.012}, {"wall_thickness_m", 0.002}, {"tip_z_m", 0.009}, {"length_m", 0.05},
                    {"velocity_m_s", {0, 0, -0.5}}, {"sides", 32}};
  DemBackend backend;
  const double dt = backend.configure(config)["dt_suggested"];
  const nlohmann::json m = backend.advance(steps(700, dt)).monitors;
  const double total = m["pile_force_n"], tip = m["pile_tip_force_n"];
  const double inner = m["pile_inner_shaft_force_n"], outer = m["pile_outer_shaft_force_n"];
  EXPECT_GT(std::abs(total), 0.0);
  // Two summation orders of the same contact forces: equal to a few roundings.
  EXPECT_NEAR(tip + inner + outer, total, 1e-12 * (std::abs(tip) + std::abs(inner) + std::abs(outer)));
  EXPECT_NEAR(m["pile_shaft_force_n"].get<double>(), inner + outer, 1e-12 * (std::abs(inner) + std::abs(outer) + std::abs(total)));
  EXPECT_GT(m["pile_plug_particles"].get<double>(), 0.0);  // 2 of this sparse bed's spheres stay in the bore
}

TEST(FoundationLoading, ThePlugColumnIsTheTopOfTheSoilInTheBore) {
  // 20 spheres of radius 1 mm stacked on the axis, touching, from z = 1 mm
  // to 39 mm above a tip at z = 0; two more thrown up the tube above them;
  // one far outside the bore. The loose volume allowed at the top is
  // 0.25 pi (3 mm)^2 x 2 mm = 14.1 mm3, 3.4 spheres of 4.19 mm3: the column's
  // top is the top of the 4th highest sphere in the bore, the stack's 2nd
  // highest (38 mm); the two thrown up do not count.
  ParticleStore p;
  for (int k = 0; k < 20; ++k) p.add_sphere(k, {0.0, 0.0, 0.001 + 0.002 * k}, 0.001, 1.0);
  p.add_sphere(20, {0.001, 0.0, 0.041}, 0.001, 1.0);
  p.add_sphere(21, {0.0, 0.001, 0.050}, 0.001, 1.0);
  p.add_sphere(22, {0.1, 0.0, 0.02}, 0.001, 1.0);  // outside the bore
  const CylinderGeometry tube{.radius = 0.004, .length = 0.3, .inner_radius = 0.003};
  const PlugColumn column = plug_column(p, tube, 0.0);
  EXPECT_EQ(column.particles, 22);
  EXPECT_NEAR(column.length, 0.038, 1e-15);
  EXPECT_NEAR(plug_column(p, tube, 0.010).length, 0.028, 1e-15);  // a tip 10 mm up
  // Three spheres hold less than the loose volume: the column counts as empty.
  EXPECT_EQ(plug_column(p, tube, 0.038).particles, 3);
  EXPECT_EQ(plug_column(p, tube, 0.038).length, 0.0);
  EXPECT_EQ(plug_column(p, tube, 0.3).particles, 0);  // a tip above everything: no column
}

}  // namespace
}  // namespace dfc::dem
