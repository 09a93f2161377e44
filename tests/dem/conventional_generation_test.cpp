// Conventional generation (conventional_generation.hpp), the route PCRM is
// measured against: placement in a walled region (radius_expansion.hpp),
// settling to an unbalanced-force ratio (settling.hpp), and the whole route on
// a small box of the chalk law of Ciantia et al. (2024).
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "dem_test_support.hpp"
#include "dfc/dem/conventional_generation.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {
namespace {

/// The chalk PSD at S = 10 with the REV's expansion schedule.
RadiusExpansionSpec chalk_radii(double porosity) {
  return {.radius_min = 3.275e-4, .radius_max = 9.025e-4, .porosity = porosity, .multiplier = 1.6, .stages = 10, .relax_steps = 300, .seed = 5};
}

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

TEST(ConventionalGeneration, PlacementInACylinderHoldsEverySphereWholeAtTheTargetSolidVolume) {
  BedRegion region;
  region.shape = BedRegion::Shape::cylinder;
  region.axis_x = 0.001;
  region.radius = 0.004;
  region.z_min = 0.002;
  region.z_max = 0.010;
  const RadiusExpansionSpec spec = chalk_radii(0.47);  // the benchmark's conventional porosity
  const ExpansionPacking packing = place_for_radius_expansion(spec, region);
  ASSERT_EQ(packing.spheres.size(), packing.final_radius.size());
  double solid = 0.0;
  for (const double r : packing.final_radius) solid += sphere_volume(r);
  const double volume = std::numbers::pi * region.radius * region.radius * (region.z_max - region.z_min);
  EXPECT_NEAR(solid / volume, 1.0 - spec.porosity, 1e-12);  // step 1 scales the radii to the exact solid volume: round-off
  for (std::size_t k = 0; k < packing.spheres.size(); ++k) {
    EXPECT_GE(clearance(packing.spheres[k], region), 0.0) << "sphere " << k << " pokes out of the cylinder";
    EXPECT_NEAR(packing.spheres[k].radius, packing.final_radius[k] / spec.multiplier, 1e-15);
  }
}

TEST(Settling, ChecksEveryIntervalAfterTheMinimumAndStopsAtTheCap) {
  // One sphere in free fall has no contacts: its ratio reads 1 (measurements.hpp)
  // and never reaches the target, so the run ends at the cap, and the checks
  // fall on steps 20, 30, 40 and 50 (every 10, from the minimum of 20).
  Simulation sim(SimulationSettings{.particle_law = test::chalk_at_s10(), .gravity = {0.0, 0.0, -981.0}, .local_damping = 0.7, .skin = 0.0, .threads = 1});
  sim.add_sphere(0, {}, 1e-3, 2556);
  std::vector<std::int64_t> checked;
  SettlingTarget target{.unbalanced_force_ratio = 0.002, .check_every = 10, .min_steps = 20, .max_steps = 50, .on_check = {}};
  target.on_check = [&](std::int64_t steps, double ratio) {
    checked.push_back(steps);
    EXPECT_EQ(ratio, 1.0);
  };
  const Settling run = settle(sim, 1e-7, target);
  EXPECT_FALSE(run.reached);
  EXPECT_EQ(run.steps, 50);
  EXPECT_EQ(run.ratio, 1.0);
  EXPECT_EQ(checked, (std::vector<std::int64_t>{20, 30, 40, 50}));
}

TEST(ConventionalGeneration, ABoxIsExpandedRelaxedSettledAtNgAndBondedToTheRatio) {
  // An 8 mm box (about 240 spheres) at 100 g: floor and four side
  // walls, the lid added by the route.
  const double side = 0.008, height = 0.008;
  BedRegion region{.shape = BedRegion::Shape::box, .min = {}, .max = {side, side, height}};
  const ContactLawSetting law = test::chalk_at_s10();
  std::vector<Wall> walls;
  const auto plane = [&](const char* name, Vec3 point, Vec3 normal) {
    walls.push_back(make_wall(name, make_plane_mesh(point, normal, side), WallMotion::prescribed, law));
  };
  plane("floor", {side / 2, side / 2, 0.0}, {0, 0, 1});
  plane("x0", {0.0, side / 2, height / 2}, {1, 0, 0});
  plane("x1", {side, side / 2, height / 2}, {-1, 0, 0});
  plane("y0", {side / 2, 0.0, height / 2}, {0, 1, 0});
  plane("y1", {side / 2, side, height / 2}, {0, -1, 0});
  ConventionalSpec spec;
  // Porosity 0.55: in a box this small (6.5 mean diameters) the looser layer
  // along its walls leaves the core jammed at the benchmark's 0.47, and still
  // at 0.5 (measured: the lid keeps 7.7 MPa however long the relaxation).
  spec.particles = chalk_radii(0.55);
  spec.region = region;
  spec.density = 2556;
  spec.fraction_of_critical = 0.3;
  spec.settling = {.unbalanced_force_ratio = 0.002, .check_every = 10, .min_steps = 200, .max_steps = 2000, .on_check = {}};
  spec.bonded_settling = spec.settling;
  spec.bonded_settling.max_steps = 40000;
  // 1 % of rho_s (1 - n) N g H, the self-weight stress at the floor (as the benchmark).
  spec.relaxed_lid_pressure = 0.01 * 2556 * (1.0 - 0.55) * 981.0 * height;
  spec.relaxation_max_steps = 40000;
  const SimulationSettings settings{.particle_law = law, .gravity = {0.0, 0.0, -981.0}, .local_damping = 0.7, .skin = 0.0, .threads = 1};
  const ConventionalBody body = generate_conventionally(spec, settings, walls);
  const Simulation& sim = *body.simulation;

  // The growth leaves the closed box jammed far above the self-weight stress
  // (the reason for the relaxation); relaxed, the lid carries at most 1 %.
  EXPECT_GT(body.lid_pressure, 100.0 * spec.relaxed_lid_pressure);
  EXPECT_TRUE(body.relaxation.reached);
  EXPECT_LE(body.relaxed_lid_pressure, spec.relaxed_lid_pressure);
  // Bonded and settled to the ratio, no sphere thrown out of the box.
  EXPECT_TRUE(body.bonded_settling.reached);
  const Measurements m = measure(sim);
  EXPECT_LE(m.unbalanced_force_ratio, 0.002);
  EXPECT_GT(sim.bond_counts().intact, sim.particles().size());  // a bonded body: coordination above 2
  const ParticleStore& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_GE(clearance({p.position[i], 0.0}, region), 0.0) << "sphere " << i << " left the box";
  // Equilibrium: the walls carry the weight. Tolerance 1 %: the small generation
  // variant at the same ratio balances within 0.5 % (docs/dem_generation.md §5).
  double carried = 0.0;
  for (const Wall& w : sim.walls()) carried -= w.force.z;
  EXPECT_NEAR(carried, m.total_weight, 0.01 * m.total_weight);
}

}  // namespace
}  // namespace dfc::dem
