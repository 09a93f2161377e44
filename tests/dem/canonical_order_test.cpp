// The canonical slot order (neighbour_search.hpp): after a rebuild the slots
// are sorted by (cell of a lattice fixed in space, particle id), so a
// particle's contact forces are summed in an order set by the positions and
// ids alone. Two consequences are checked here: the same body given in any
// slot order runs to the same bits (through rebuilds), and a part of a body with a halo around
// it (what a process of a decomposed run holds) computes, for the particles
// far enough inside, the same bits as the whole body.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/portable_random.hpp"

namespace dfc::dem {
namespace {

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

/// A jittered lattice of 20^3 overlapping spheres (overlaps up to ~20 % of a
/// radius) with random velocities and spins, under gravity, linear law with
/// friction and damping; the one sphere of the largest radius sits at the
/// centre, so that a part holding the centre has the whole body's cell size.
struct Sphere {
  std::int64_t id;
  Vec3 x, v, w;
  double r;
};

std::vector<Sphere> jittered_lattice() {
  PortableRandom random(17);
  std::vector<Sphere> spheres;
  const double a = 1.2e-3;
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) {
        const auto jitter = [&] { return random.uniform(-3e-5, 3e-5); };
        const Vec3 x{a * i + jitter(), a * j + jitter(), a * k + jitter()};
        const Vec3 v{random.uniform(-1e-2, 1e-2), random.uniform(-1e-2, 1e-2), random.uniform(-1e-2, 1e-2)};
        const Vec3 w{random.uniform(-10, 10), random.uniform(-10, 10), random.uniform(-10, 10)};
        const bool centre = i == 10 && j == 10 && k == 10;
        spheres.push_back({std::int64_t(7 + 3 * spheres.size()), x, v, w, centre ? 6.3e-4 : random.uniform(5.7e-4, 6.2e-4)});
      }
  return spheres;
}

/// Runs `steps` steps of the spheres (in the order given) and returns each
/// particle's position, velocity and force by id.
struct RunResult {
  std::map<std::int64_t, std::array<Vec3, 3>> state;
  std::size_t rebuilds = 0;
};

RunResult run_spheres(const std::vector<Sphere>& spheres, int steps) {
  Simulation sim(SimulationSettings{
      .particle_law = test::linear(1e5, 5e4, 0.5, 0.2), .gravity = {0, 0, -98.1}, .local_damping = 0.1, .skin = 1e-4, .threads = 1});
  for (const auto& s : spheres) sim.add_sphere(s.id, s.x, s.r, 2650.0);
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    p.velocity[i] = spheres[i].v;
    p.angular_velocity[i] = spheres[i].w;
  }
  for (int s = 0; s < steps; ++s) sim.step(2e-7);
  const ParticleStore& after = sim.particles();
  std::map<std::int64_t, std::array<Vec3, 3>> state;
  for (std::size_t i = 0; i < after.size(); ++i) state[after.id[i]] = {after.position[i], after.velocity[i], after.force[i]};
  return {state, sim.rebuild_count()};
}

std::size_t fields_that_differ(const RunResult& a, const RunResult& b) {
  std::size_t differ = 0;
  for (const auto& [id, state] : a.state)
    for (std::size_t k = 0; k < 3; ++k) differ += same_bits(state[k], b.state.at(id)[k]) ? 0 : 1;
  return differ;
}

TEST(CanonicalOrder, TheSameBodyInAnotherSlotOrderRunsToTheSameBits) {
  // The overlaps push the lattice apart: the lists are rebuilt along the way.
  const std::vector<Sphere> spheres = jittered_lattice();
  std::vector<Sphere> shuffled = spheres;
  PortableRandom random(5);
  for (std::size_t k = shuffled.size() - 1; k > 0; --k) std::swap(shuffled[k], shuffled[std::size_t(random.uniform() * double(k + 1))]);
  constexpr int steps = 300;
  const RunResult given = run_spheres(spheres, steps);
  const RunResult other = run_spheres(shuffled, steps);
  EXPECT_GT(given.rebuilds, 2u);
  ASSERT_EQ(given.state.size(), other.state.size());
  EXPECT_EQ(fields_that_differ(given, other), 0u) << "fields of particles that differ between the two slot orders";
}

TEST(CanonicalOrder, APartOfTheBodyWithAHaloComputesItsInsideToTheSameBitsAsTheWholeBody) {
  const std::vector<Sphere> whole = jittered_lattice();
  // The part: a cube of 5 mm around the centre (the particles checked) and a
  // halo of 4 neighbour-search reaches (2 r_max + skin) around it, enough for
  // 3 steps: a wrong force at the part's edge travels inwards one contact a step.
  const double reach = 2 * 6.3e-4 + 1e-4;
  const Vec3 centre{12e-3, 12e-3, 12e-3};
  const auto within = [&](const Vec3& x, double half) {
    return std::abs(x.x - centre.x) < half && std::abs(x.y - centre.y) < half && std::abs(x.z - centre.z) < half;
  };
  std::vector<Sphere> part;
  for (const auto& s : whole)
    if (within(s.x, 2.5e-3 + 4 * reach)) part.push_back(s);
  // As another process would receive them: in another order.
  std::reverse(part.begin(), part.end());
  std::rotate(part.begin(), part.begin() + std::ptrdiff_t(part.size() / 3), part.end());
  ASSERT_LT(part.size(), whole.size() / 2);

  constexpr int steps = 3;
  const auto in_whole = run_spheres(whole, steps).state;
  const auto in_part = run_spheres(part, steps).state;
  std::size_t checked = 0, differ = 0;
  for (const auto& s : whole) {
    if (!within(s.x, 2.5e-3)) continue;
    ++checked;
    const auto& a = in_whole.at(s.id);
    const auto& b = in_part.at(s.id);
    for (std::size_t k = 0; k < 3; ++k) differ += same_bits(a[k], b[k]) ? 0 : 1;
  }
  EXPECT_GT(checked, 50u);
  EXPECT_EQ(differ, 0u) << "fields of the " << checked << " inside particles that differ from the whole body's";
  // The halo's edge is wrong (it misses partners outside the part): the check can fail.
  std::size_t edge_differ = 0;
  for (const auto& s : part)
    if (!within(s.x, 2.5e-3 + 3 * reach)) edge_differ += same_bits(in_whole.at(s.id)[2], in_part.at(s.id)[2]) ? 0 : 1;
  EXPECT_GT(edge_differ, 0u);
}

}  // namespace
}  // namespace dfc::dem
