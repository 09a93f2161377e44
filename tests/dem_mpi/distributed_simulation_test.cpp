// DistributedSimulation (distributed_simulation.hpp): a body decomposed over
// the processes of the run gives the whole body's bits. Every test runs on
// every process count of tests/dem_mpi/CMakeLists.txt (1 to 4) and compares
// with the same body stepped alone on rank 0.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <mpi.h>

#include "dem_test_support.hpp"
#include "dfc/dem/distributed_simulation.hpp"
#include "dfc/dem/portable_random.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

/// Weak parallel bonds (Potyondy & Cundall 2004) between touching spheres of
/// 1 mm, so that a squeezed block breaks some of them.
ContactLawSetting weak_pbond() {
  return make_contact_law({{"law", "linear_pbond"}, {"emod_pa", 5e7}, {"pb_emod_pa", 5e7}, {"pb_ten_pa", 2e5}, {"pb_coh_pa", 2e5},
                           {"friction", 0.5}, {"bond_gap_m", 2e-5}});
}

/// The set-up of a run, made on every process (particles on rank 0 only).
using Setup = std::function<void(Simulation&, bool with_particles)>;

/// A bonded block of 16 x 8 x 12 jittered spheres on a floor under 1000 g,
/// squeezed by a platen from above, sheared and swirling (random velocities
/// and spins): bonds break, particles cross the boxes' boundaries.
void squeezed_block(Simulation& sim, bool with_particles) {
  const double a = 2e-3;
  sim.add_wall(make_wall("floor", make_plane_mesh({0.016, 0.008, -1.02e-3}, {0, 0, 1}, 0.05), WallMotion::prescribed, test::linear(5e5, 2e5)));
  sim.add_wall(make_wall("platen", make_plane_mesh({0.016, 0.008, 11 * a + 1.02e-3}, {0, 0, -1}, 0.05), WallMotion::prescribed,
                         test::linear(5e5, 2e5), {0, 0, -0.25}));
  if (!with_particles) return;
  PortableRandom random(11);
  std::int64_t id = 1000;
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 16; ++i) {
        const auto jitter = [&] { return random.uniform(-5e-6, 5e-6); };
        sim.add_sphere(id, {a * i + jitter(), a * j + jitter(), a * k + jitter()}, random.uniform(0.995e-3, 1.0e-3), 2650.0);
        id += 1 + std::int64_t(random.uniform() * 3);  // ids with gaps, not in any spatial order
      }
  // Four loose spheres sliding along the floor beside the block, across the
  // first cut (x = 15 mm): particles that change process on any process count.
  for (int k = 0; k < 4; ++k) sim.add_sphere(900 + k, {4e-3 + 3e-3 * k, -4e-3, 0}, 1e-3, 2650.0);
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.id[i] < 1000) {
      p.velocity[i] = {3.0, 0, 0};
      continue;
    }
    // Sheared along x (the longest edge, which the first cut crosses): +-0.5 m/s at the top and bottom.
    const double shear = 0.5 * (p.position[i].z - 5.5 * a) / (5.5 * a);
    p.velocity[i] = {shear + random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3)};
    p.angular_velocity[i] = {random.uniform(-100, 100), random.uniform(-100, 100), random.uniform(-100, 100)};
  }
}

/// Two bonded spheres pulled apart along x until the bond breaks and they
/// fly far apart (the pair stays a broken bond at any distance), among 60
/// unbonded spectators that keep the bisection's cut between the two.
void pulled_bond(Simulation& sim, bool with_particles) {
  if (!with_particles) return;
  sim.add_sphere(1, {-0.5e-3 - 1e-6, 0, 0}, 0.5e-3, 2650.0);
  sim.add_sphere(2, {0.5e-3 + 1e-6, 0, 0}, 0.5e-3, 2650.0);
  std::int64_t id = 10;
  for (int side : {-1, 1})
    for (int k = 0; k < 30; ++k) sim.add_sphere(id++, {side * (4e-3 + 1.5e-3 * (k % 5)), 5e-3 + 1.5e-3 * (k / 5), 0}, 0.5e-3, 2650.0);
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] == 1 || p.id[i] == 2) p.velocity[i] = {p.id[i] == 1 ? -2.0 : 2.0, 0, 0};
}

/// A bonded pair in the middle of four clusters of 7 x 7 spheres that do not
/// touch (enough that two spheres changing box leave the load within the
/// decomposition's tolerance, so it keeps its cuts), moving diagonally at 2 m/s in +x and +y. The skin (kCrossingSkin)
/// holds the lists until the pair has moved 3.3 mm along each axis: the
/// trailing sphere then lies across both cuts of four boxes from where the
/// first decomposition put it (the x cut, then the other half's y cut).
constexpr double kCrossingSkin = 9.4e-3;

void pair_crossing_cuts(Simulation& sim, bool with_particles) {
  if (!with_particles) return;
  std::int64_t id = 100;
  for (const int sx : {-1, 1})
    for (const int sy : {-1, 1})
      for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j) sim.add_sphere(id++, {sx * (4.5e-3 + 1.2e-3 * i), sy * (4.5e-3 + 1.2e-3 * j), 0}, 0.5e-3, 2650.0);
  const double lead = -0.4e-3, apart = (1e-3 + 2e-6) / std::sqrt(2.0);  // 2 um apart: bonded (weak_pbond's bond_gap_m)
  sim.add_sphere(1, {lead, lead, 0}, 0.5e-3, 2650.0);
  sim.add_sphere(2, {lead - apart, lead - apart, 0}, 0.5e-3, 2650.0);
  ParticleStore& p = sim.particles_for_edit();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] < 100) p.velocity[i] = {2.0, 2.0, 0};
}

/// A wall's loads from the particles: force, moment, force on the particles, then each vertex's force.
std::vector<Vec3> wall_loads(const Wall& wall) {
  std::vector<Vec3> loads{wall.force, wall.moment, wall.force_on_particles};
  loads.insert(loads.end(), wall.vertex_force.begin(), wall.vertex_force.end());
  return loads;
}

/// The monitors of an advance that the whole body's measure() gives.
std::vector<double> monitors(const Measurements& m, const Vec3& momentum) {
  return {double(m.particle_count), double(m.pair_contact_count), double(m.wall_contact_count), m.coordination_number, m.kinetic_energy,
          m.total_weight, m.unbalanced_force_ratio, momentum.x, momentum.y, momentum.z};
}

struct Outcome {
  std::vector<ParticleRecord> particles;  ///< by id (rank 0)
  std::vector<std::vector<Vec3>> walls;   ///< wall_loads of each wall
  std::vector<double> monitors;
  BondCounts bonds;
  std::size_t rebuilds = 0, migrated = 0, recuts = 0;
};

SimulationSettings settings(const ContactLawSetting& law, Vec3 gravity, double skin = 0.0) {
  return {.particle_law = law, .gravity = gravity, .local_damping = 0.05, .skin = skin, .threads = 1};
}

Outcome run_decomposed(const Setup& setup, const ContactLawSetting& law, Vec3 gravity, int steps, double step_fraction) {
  Simulation local(settings(law, gravity));
  setup(local, world_rank() == 0);
  DistributedSimulation body(MPI_COMM_WORLD, local);
  const double dt = step_fraction * body.critical_timestep();
  std::size_t migrated = 0, decompositions = 0;
  for (int s = 0; s < steps; ++s) {
    body.step(dt);
    if (body.stats().decompositions == decompositions) continue;
    decompositions = body.stats().decompositions;
    migrated += body.stats().migrated;
  }
  std::size_t migrated_everywhere = 0;
  MPI_Allreduce(&migrated, &migrated_everywhere, 1, MPI_UNSIGNED_LONG, MPI_SUM, MPI_COMM_WORLD);
  std::vector<std::vector<Vec3>> walls;
  for (const Wall& wall : local.walls()) walls.push_back(wall_loads(wall));
  return {body.gather_particles(0), walls, monitors(body.measure(), body.momentum()), body.bond_counts(), body.stats().decompositions,
          migrated_everywhere, body.stats().recuts};
}

Outcome run_whole(const Setup& setup, const ContactLawSetting& law, Vec3 gravity, int steps, double step_fraction, double skin = 0.0) {
  Simulation sim(settings(law, gravity, skin));
  setup(sim, true);
  const double dt = step_fraction * sim.critical_timestep();
  for (int s = 0; s < steps; ++s) sim.step(dt);
  Outcome out;
  const ParticleStore& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i)
    out.particles.push_back({p.id[i], p.position[i], p.velocity[i], p.angular_velocity[i], p.force[i], p.moment[i], p.radius[i], p.mass[i],
                             p.inertia[i], 0, p.material[i]});
  std::sort(out.particles.begin(), out.particles.end(), [](const auto& x, const auto& y) { return x.id < y.id; });
  for (const Wall& wall : sim.walls()) out.walls.push_back(wall_loads(wall));
  out.monitors = monitors(measure(sim), sim.momentum());
  out.bonds = sim.bond_counts();
  out.rebuilds = sim.rebuild_count();
  return out;
}

/// Fields (position, velocity, spin, force, moment) that differ from the whole body's.
std::size_t fields_that_differ(const Outcome& decomposed, const Outcome& whole) {
  std::size_t differ = 0;
  for (std::size_t k = 0; k < whole.particles.size(); ++k) {
    const ParticleRecord& a = decomposed.particles[k];
    const ParticleRecord& b = whole.particles[k];
    differ += a.id != b.id;
    differ += !same_bits(a.position, b.position) + !same_bits(a.velocity, b.velocity) + !same_bits(a.angular_velocity, b.angular_velocity) +
              !same_bits(a.force, b.force) + !same_bits(a.moment, b.moment);
  }
  return differ;
}

TEST(DistributedSimulation, ASqueezedBondedBlockAndItsWallsHaveTheWholeBodysBitsOnAnyProcessCount) {
  const ContactLawSetting law = weak_pbond();
  constexpr int steps = 3500;
  const Outcome decomposed = run_decomposed(squeezed_block, law, {0, 0, -9810}, steps, 0.3);
  if (world_rank() != 0) return;
  const Outcome whole = run_whole(squeezed_block, law, {0, 0, -9810}, steps, 0.3);
  ASSERT_EQ(decomposed.particles.size(), whole.particles.size());
  EXPECT_EQ(fields_that_differ(decomposed, whole), 0u);
  // The walls' loads, summed from the contacts of every process in the whole body's order.
  ASSERT_EQ(decomposed.walls.size(), whole.walls.size());
  for (std::size_t w = 0; w < whole.walls.size(); ++w) {
    ASSERT_EQ(decomposed.walls[w].size(), whole.walls[w].size());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < whole.walls[w].size(); ++k) differ += !same_bits(decomposed.walls[w][k], whole.walls[w][k]);
    EXPECT_EQ(differ, 0u) << "wall " << w;
    EXPECT_GT(norm(whole.walls[w][0]), 0.0) << "wall " << w << " carries no load: the check could not fail";
  }
  EXPECT_EQ(decomposed.bonds.intact, whole.bonds.intact);
  EXPECT_EQ(decomposed.bonds.broken_tension + decomposed.bonds.broken_shear, whole.bonds.broken_tension + whole.bonds.broken_shear);
  // The monitors (measure and momentum), exact sums over the processes' own parts.
  ASSERT_EQ(decomposed.monitors.size(), whole.monitors.size());
  for (std::size_t k = 0; k < whole.monitors.size(); ++k)
    EXPECT_EQ(std::memcmp(&decomposed.monitors[k], &whole.monitors[k], sizeof(double)), 0)
        << "monitor " << k << ": " << decomposed.monitors[k] << " against " << whole.monitors[k];
  EXPECT_GT(whole.monitors[1], 1000.0);  // pair contacts: the counts can differ
  // What makes the check able to fail: rebuilds (each one a decomposition),
  // broken bonds, and (on more than one process) particles that changed owner.
  EXPECT_GT(whole.rebuilds, 3u);
  // A decomposition follows at once the step that calls for a rebuild; the
  // whole body rebuilds at the start of the next step: one more if the last step called for one.
  EXPECT_GE(decomposed.rebuilds, whole.rebuilds);
  EXPECT_LE(decomposed.rebuilds, whole.rebuilds + 1);
  EXPECT_GT(whole.bonds.broken_tension + whole.bonds.broken_shear, 10);
  EXPECT_GT(whole.bonds.intact, 1000);
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks > 1) {
    EXPECT_GT(decomposed.migrated, 0u);
  }
  // The boxes were cut anew only where the load had drifted: not at every decomposition.
  EXPECT_GE(decomposed.recuts, 1u);
  EXPECT_LT(decomposed.recuts, decomposed.rebuilds);
}

TEST(DistributedSimulation, ABondAcrossABoundaryBreaksAndItsPartnersFlyApartAsInTheWholeBody) {
  const ContactLawSetting law = weak_pbond();
  constexpr int steps = 2000;
  const Outcome decomposed = run_decomposed(pulled_bond, law, {}, steps, 0.3);
  if (world_rank() != 0) return;
  const Outcome whole = run_whole(pulled_bond, law, {}, steps, 0.3);
  ASSERT_EQ(decomposed.particles.size(), whole.particles.size());
  EXPECT_EQ(fields_that_differ(decomposed, whole), 0u);
  EXPECT_EQ(whole.bonds.intact, 0);
  EXPECT_EQ(whole.bonds.broken_tension + whole.bonds.broken_shear, 1);
  EXPECT_EQ(decomposed.bonds.broken_tension + decomposed.bonds.broken_shear, 1);
  // Far apart at the end: beyond the halo (a search reach, 2 r + skin = 1.1
  // mm), each held by the other's process only as the partner of the broken bond.
  const auto distance = norm(whole.particles[1].position - whole.particles[0].position);
  EXPECT_GT(distance, 3 * 1.1e-3);
}

TEST(DistributedSimulation, ASphereThatCrossesTwoCutsBeforeTheNextDecompositionMovesWithItsBondAsInTheWholeBody) {
  const ContactLawSetting law = weak_pbond();
  Simulation local(settings(law, {}, kCrossingSkin));
  pair_crossing_cuts(local, world_rank() == 0);
  DistributedSimulation body(MPI_COMM_WORLD, local);
  const double dt = 0.3 * body.critical_timestep();
  // 3.6 mm along each axis: past the rebuild at 3.3 mm, far from the next.
  const int steps = int(std::ceil(3.6e-3 / (2.0 * dt)));
  body.step(dt);
  const std::vector<ParticleRecord> first = body.gather_particles(0);
  for (int s = 1; s < steps; ++s) body.step(dt);
  const Outcome decomposed{body.gather_particles(0), {}, {}, body.bond_counts(), body.stats().decompositions, 0, body.stats().recuts};
  if (world_rank() != 0) return;
  const Outcome whole = run_whole(pair_crossing_cuts, law, {}, steps, 0.3, kCrossingSkin);
  ASSERT_EQ(decomposed.particles.size(), whole.particles.size());
  EXPECT_EQ(fields_that_differ(decomposed, whole), 0u);
  EXPECT_EQ(decomposed.bonds.intact, 1);
  EXPECT_EQ(whole.bonds.intact, 1);
  // One decomposition after the first, as the whole body rebuilt once after its first build.
  EXPECT_EQ(whole.rebuilds, 2u);
  EXPECT_EQ(decomposed.rebuilds, 2u);
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks != 4) return;
  // On four boxes: the trailing sphere (id 2) went from one box to the one
  // diagonally across, past both cuts, at that one decomposition. The boxes
  // are the first decomposition's (kept: the load did not drift), computed
  // here from the same points.
  ASSERT_EQ(decomposed.recuts, 1u);
  Simulation start(settings(law, {}, kCrossingSkin));
  pair_crossing_cuts(start, true);
  const std::vector<double> weights(start.particles().size(), 1.0);
  const RcbDecomposition boxes(start.particles().position, weights, ranks);
  const auto owner_of = [](const std::vector<ParticleRecord>& records, std::int64_t id) {
    return std::find_if(records.begin(), records.end(), [&](const ParticleRecord& r) { return r.id == id; })->owner;
  };
  const SpaceBox& from = boxes.box(owner_of(first, 2));
  const SpaceBox& to = boxes.box(owner_of(decomposed.particles, 2));
  EXPECT_LE(from.hi.x, to.lo.x);
  EXPECT_LE(from.hi.y, to.lo.y);
}

TEST(DistributedSimulation, AnUnstableStepFailsOnEveryProcessWithTheSameKindOfError) {
  // Twenty times the critical step: an overlap beyond half a radius within a
  // few steps, seen by the processes that hold that contact; all must throw
  // (none may wait in a collective for the others).
  Simulation local(settings(weak_pbond(), {0, 0, -9810}));
  squeezed_block(local, world_rank() == 0);
  DistributedSimulation body(MPI_COMM_WORLD, local);
  const double dt = 20.0 * body.critical_timestep();
  EXPECT_THROW(
      {
        for (int s = 0; s < 200; ++s) body.step(dt);
      },
      SolverError);
}

TEST(DistributedSimulation, APeriodicCellIsRefusedWithTheKeyThatRunsItOnOneProcess) {
  Simulation local(settings(weak_pbond(), {0, 0, 0}));
  local.set_periodic_cell({.lo = {0, 0, 0}, .hi = {0.02, 0.02, 0.02}, .periodic = {true, true, true}, .strain_rate = {}});
  try {
    const DistributedSimulation body(MPI_COMM_WORLD, local);
    ADD_FAILURE() << "a periodic cell was decomposed";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("participants.dem.mpi_ranks to 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dfc::dem
