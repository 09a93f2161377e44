#include "dfc/dem/conventional_generation.hpp"

#include <chrono>
#include <numbers>

#include "dfc/common/errors.hpp"
#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/region_config.hpp"
#include "dfc/dem/wall_builders.hpp"

namespace dfc::dem {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double region_volume(const BedRegion& r) {
  const auto [lo, hi] = region_bounds(r);
  return r.shape == BedRegion::Shape::box ? (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z) : std::numbers::pi * r.radius * r.radius * (hi.z - lo.z);
}

GenerationStage settling_stage(Simulation& sim, double dt, const SettlingTarget& target) {
  const auto start = std::chrono::steady_clock::now();
  const Settling run = settle(sim, dt, target);
  return {.steps = run.steps, .seconds = seconds_since(start), .reached = run.reached, .ratio = run.ratio};
}

/// Steps the closed container until its lid carries at most `pressure`
/// (checked every check_every steps), at most max_steps.
GenerationStage relax_until_lid_pressure(Simulation& sim, double dt, double top_area, double pressure, std::int64_t check_every,
                                         std::int64_t max_steps) {
  const auto start = std::chrono::steady_clock::now();
  GenerationStage out{.steps = 0, .seconds = 0.0, .reached = false, .ratio = 0.0};
  const Wall& lid = sim.walls().back();
  while (out.steps < max_steps && !out.reached) {
    sim.step(dt, ContactRecord::gathered_only);  // wall contacts are always written
    ++out.steps;
    out.reached = out.steps % check_every == 0 && lid.force.z / top_area <= pressure;
  }
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace

ConventionalBody generate_conventionally(const ConventionalSpec& spec, const SimulationSettings& settings, const std::vector<Wall>& walls) {
  if (walls.empty()) throw UserError("conventional generation needs the container's walls (a floor at least)");
  ConventionalBody out;

  // 1. Radius expansion in the closed container, without gravity.
  auto start = std::chrono::steady_clock::now();
  SimulationSettings weightless = settings;
  weightless.gravity = {};
  weightless.install_bonds_at_start = false;
  Simulation closed(weightless);
  for (const Wall& w : walls) closed.add_wall(w);
  const auto [lo, hi] = region_bounds(spec.region);
  const Vec3 top{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), hi.z};
  closed.add_wall(make_wall("lid", make_plane_mesh(top, {0.0, 0.0, -1.0}, norm(hi - lo)), WallMotion::prescribed, walls.front().law));
  const ExpansionPacking packing = place_for_radius_expansion(spec.particles, spec.region);
  for (std::size_t k = 0; k < packing.spheres.size(); ++k)
    closed.add_sphere(std::int64_t(k), packing.spheres[k].centre, packing.spheres[k].radius, spec.density);
  out.expansion_report = expand_radii(closed, packing.final_radius, spec.particles, spec.fraction_of_critical, region_volume(spec.region));
  closed.step(spec.fraction_of_critical * closed.critical_timestep());  // complete contact outputs for the ratio
  const double top_area = region_volume(spec.region) / (hi.z - lo.z);
  out.lid_pressure = closed.walls().back().force.z / top_area;
  out.expansion = {.steps = out.expansion_report.steps + 1, .seconds = seconds_since(start), .reached = true,
                   .ratio = measure(closed).unbalanced_force_ratio};

  // 2. Relaxation in the closed container: the growth leaves the packing
  // jammed at megapascals (each stage's 300 steps do not let it rearrange);
  // taking the lid off then would throw the top spheres out of the container.
  out.relaxation = relax_until_lid_pressure(closed, spec.fraction_of_critical * closed.critical_timestep(), top_area, spec.relaxed_lid_pressure,
                                            spec.settling.check_every, spec.relaxation_max_steps);
  out.relaxed_lid_pressure = closed.walls().back().force.z / top_area;

  // 3. The lid off, N g on: the packing (positions, radii and pair history;
  // the velocities left behind, at rest) in a simulation with gravity.
  SimulationSettings loaded = settings;
  loaded.install_bonds_at_start = false;
  out.simulation = std::make_unique<Simulation>(loaded);
  Simulation& sim = *out.simulation;
  for (const Wall& w : walls) sim.add_wall(w);
  const ParticleStore& p = closed.particles();
  for (std::size_t i = 0; i < p.size(); ++i) sim.add_sphere(p.id[i], p.position[i], p.radius[i], spec.density);
  sim.seed_pair_history(archive_history(closed.pair_contacts(), p), false);
  out.dt = spec.fraction_of_critical * sim.critical_timestep();
  out.settling = settling_stage(sim, out.dt, spec.settling);

  // 4. Bonds with zero load, then settling again: the bonds take up the weight.
  start = std::chrono::steady_clock::now();
  sim.install_bonds_now();
  out.bonded_settling = settling_stage(sim, out.dt, spec.bonded_settling);
  out.bonded_settling.seconds = seconds_since(start);
  return out;
}

}  // namespace dfc::dem
