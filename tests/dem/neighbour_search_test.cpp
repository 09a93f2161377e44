// Linked-cell search against brute force, and contact history across rebuilds.
#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/neighbour_search.hpp"
#include "dfc/dem/portable_random.hpp"
#include "dfc/dem/triangle_geometry.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

ParticleStore random_packing(std::size_t n, std::uint64_t seed) {
  PortableRandom random(seed);
  ParticleStore p;
  for (std::size_t i = 0; i < n; ++i)
    p.add_sphere(std::int64_t(1000 + i), {random.uniform(0, 0.02), random.uniform(0, 0.02), random.uniform(0, 0.03)}, random.uniform(4e-4, 6e-4),
                 2650.0);
  return p;
}

/// Every (particle slot, facet) with distance(centre, facet) < r + skin, sorted.
std::vector<std::pair<std::uint32_t, std::uint32_t>> facet_candidates_by_brute_force(const ParticleStore& p, const Wall& wall, double skin) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::uint32_t i = 0; i < p.size(); ++i)
    for (std::uint32_t f = 0; f < wall.facet_count(); ++f) {
      const auto& v = wall.facets[f];
      if (distance_to_triangle(p.position[i], wall.vertices[v[0]], wall.vertices[v[1]], wall.vertices[v[2]]) < p.radius[i] + skin)
        expected.emplace_back(i, f);
    }
  return expected;
}

TEST(NeighbourSearch, CandidatePairsEqualBruteForceOnARandomPacking) {
  ParticleStore p = random_packing(3000, 42);
  const double skin = 1e-4;
  std::vector<std::uint32_t> order;
  const CellGrid grid = build_cell_grid(p, 2 * 6e-4 + skin, 1, order);
  p.permute(order);
  std::vector<std::uint32_t> first, second;
  find_pair_candidates(grid, p, skin, 2, first, second);

  std::set<std::pair<std::int64_t, std::int64_t>> found, expected;
  for (std::size_t k = 0; k < first.size(); ++k)
    found.emplace(std::min(p.id[first[k]], p.id[second[k]]), std::max(p.id[first[k]], p.id[second[k]]));
  EXPECT_EQ(found.size(), first.size()) << "a pair is listed twice";
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double reach = p.radius[i] + p.radius[j] + skin;
      if (norm2(p.position[i] - p.position[j]) < reach * reach) expected.emplace(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]));
    }
  EXPECT_GT(expected.size(), 500u);  // the packing is dense enough to mean something
  EXPECT_EQ(found, expected);
}

TEST(NeighbourSearch, CandidatePairsEqualBruteForceAcrossTheOriginAndFarFromIt) {
  // The grid's cells are those of a lattice anchored at 0 (the canonical
  // order): a body straddling 0 and one far from it are searched as fully.
  for (const Vec3 shift : {Vec3{-0.01, -0.013, -0.004}, Vec3{-57.3, 1e3 + 0.1234567, 0.0}}) {
    ParticleStore p = random_packing(3000, 43);
    for (auto& x : p.position) x = x + shift;
    const double skin = 1e-4;
    std::vector<std::uint32_t> order;
    const CellGrid grid = build_cell_grid(p, 2 * 6e-4 + skin, 1, order);
    p.permute(order);
    std::vector<std::uint32_t> first, second;
    find_pair_candidates(grid, p, skin, 2, first, second);
    std::set<std::pair<std::int64_t, std::int64_t>> found, expected;
    for (std::size_t k = 0; k < first.size(); ++k)
      found.emplace(std::min(p.id[first[k]], p.id[second[k]]), std::max(p.id[first[k]], p.id[second[k]]));
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = i + 1; j < p.size(); ++j) {
        const double reach = p.radius[i] + p.radius[j] + skin;
        if (norm2(p.position[i] - p.position[j]) < reach * reach) expected.emplace(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]));
      }
    EXPECT_GT(expected.size(), 500u);
    EXPECT_EQ(found.size(), first.size()) << "a pair is listed twice";
    EXPECT_EQ(found, expected) << "shift " << shift.x << ", " << shift.y << ", " << shift.z;
  }
}

TEST(NeighbourSearch, FacetCandidatesEqualBruteForce) {
  ParticleStore p = random_packing(3000, 7);
  const double skin = 1e-4;
  std::vector<std::uint32_t> order;
  const CellGrid grid = build_cell_grid(p, 2 * 6e-4 + skin, 1, order);
  p.permute(order);
  const Wall pile = make_wall("pile", make_closed_cylinder_mesh({.axis_x = 0.01, .axis_y = 0.01, .tip_z = 0.01, .radius = 3e-3, .length = 0.05, .sides = 12}),
                              WallMotion::prescribed, test::linear(1e5, 1e5));
  const auto found = find_facet_candidates(grid, p, pile, skin, 6e-4, 2);
  const auto expected = facet_candidates_by_brute_force(p, pile, skin);
  EXPECT_GT(expected.size(), 50u);
  EXPECT_EQ(found, expected);
}

TEST(NeighbourSearch, FacetCandidatesOfAnOpenTubeEqualBruteForce) {
  // The open pile's long, thin shaft facets (48 sides, 30 mm long) and its
  // annulus, where the search culls most of each facet's box by
  // TriangleDistanceBound: the candidates must still be exactly those of the
  // exact distance test, including the spheres placed at the reach itself.
  ParticleStore p = random_packing(3000, 11);
  const double skin = 1e-4;
  const Wall pile = make_wall("pile",
                              make_open_tube_mesh({.axis_x = 0.01, .axis_y = 0.01, .tip_z = 0.012, .radius = 4e-3, .length = 0.03, .sides = 48,
                                                   .inner_radius = 3e-3}),
                              WallMotion::prescribed, test::linear(1e5, 1e5));
  // Spheres whose surface is exactly the skin away from a shaft facet's face.
  for (std::uint32_t f = 100; f < 110; ++f) {
    const auto& v = pile.facets[f];
    const Vec3 centre = (1.0 / 3.0) * (pile.vertices[v[0]] + pile.vertices[v[1]] + pile.vertices[v[2]]);
    const Vec3 n = triangle_normal(pile.vertices[v[0]], pile.vertices[v[1]], pile.vertices[v[2]]);
    p.add_sphere(std::int64_t(9000 + f), centre + (5e-4 + skin) * n, 5e-4, 2650.0);
  }
  std::vector<std::uint32_t> order;
  const CellGrid grid = build_cell_grid(p, 2 * 6e-4 + skin, 1, order);
  p.permute(order);
  const auto found = find_facet_candidates(grid, p, pile, skin, 6e-4, 2);
  const auto expected = facet_candidates_by_brute_force(p, pile, skin);
  EXPECT_GT(expected.size(), 500u);
  EXPECT_EQ(found, expected);
}

TEST(ContactHistory, ShearHistorySurvivesANeighbourListRebuild) {
  const ContactLawSetting law = test::linear(1e5, 1e5, 0.5);
  Simulation sim = test::undamped(law);
  // Ids in reverse slot order: the pair is oriented by id, not by slot.
  sim.add_sphere(9, {0, 0, 0}, 1e-3, 2650);
  sim.add_sphere(3, {0, 0, 2e-3 - 2e-5}, 1e-3, 2650);
  sim.particles_for_edit().velocity[1] = {1e-3, 0, 0};  // shear the contact
  const double dt = 1e-7;
  for (int s = 0; s < 10; ++s) sim.step(dt);
  ASSERT_EQ(sim.pair_contacts().size(), 1u);
  const auto before = sim.pair_contacts().history;
  ASSERT_GT(std::abs(before[0]), 0.0);

  // Stop the motion (any edit of the particles forces a rebuild) and take one step:
  // with no slip, the carried shear force must come back unchanged.
  const std::size_t rebuilds = sim.rebuild_count();
  ParticleStore& p = sim.particles_for_edit();
  for (auto& v : p.velocity) v = {};
  for (auto& w : p.angular_velocity) w = {};
  sim.step(dt);
  EXPECT_EQ(sim.rebuild_count(), rebuilds + 1);
  const auto after = sim.pair_contacts().history;
  ASSERT_EQ(after.size(), before.size());
  // Equal up to the rotation with the contact plane, which turned during the
  // last move by ~ v dt / (2 r) = 5e-8 rad: 1e-6 of |F_s|. A lost history would be 0.
  const double magnitude = std::sqrt(before[0] * before[0] + before[1] * before[1] + before[2] * before[2]);
  for (std::size_t k = 0; k < before.size(); ++k) EXPECT_NEAR(after[k], before[k], 1e-6 * magnitude);
}

}  // namespace
}  // namespace dfc::dem
