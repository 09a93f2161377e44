// generation_compare: PCRM against conventional generation of the same bonded
// body at N g (docs/dem_generation.md, "PCRM against conventional generation";
// run by bench/generation_compare.sh).
//
//   generation_compare --scenario FILE [--radius-m R] [--height-m H] [--sides 48]
//                      [--ratio 0.002] [--max-steps 2000000] [--unbonded-max-steps M] [--threads 1]
//                      [--porosity N] [--pcrm-only] [--require-equilibrium]
//
// FILE is a coupled generation scenario (tests/e2e/scenarios/centrifuge_generation_small.json):
// its DEM section (generator "pcrm", a cylinder region, a floor) and its
// gravity. Both routes build the same domain, the cylinder of radius R and
// height H (default: the scenario's), in the same rigid walls: the floor and
// a side wall of facets, a polygon of `sides` panels inscribed in the circle,
// standing in for the continuum's coupling wall, so that the comparison
// measures the generation, not the coupling:
//   pcrm          the model builder's route (pcrm_generation.hpp: REV, replication,
//                 stress scaling, trimming and seating on both walls), then
//                 settling under N g to the ratio;
//   conventional  conventional_generation.hpp at the same radii and the PCRM
//                 body's porosity (the REV's, over the polygon's area).
// Both stop on the same unbalanced-force ratio (settling.hpp: checked every
// 10 steps after 200, as the coupled scenario's run.stop_when). Prints one JSON
// object per route: spheres, bonds, the steps and wall time of each stage, and
// the Love-Weber stress over horizontal slices one REV cell high, the top and
// bottom slices left out (the scenario's profile rule, particle_stress.hpp),
// against sigma_v = gamma (z_s - z) and sigma_h = K0 sigma_v; the wall time
// of each stage and the CPU time of each route. Progress on stderr.
// --max-steps caps each settling stage and the conventional relaxation (a
// route that hits it reports "reached": false and the ratio it got to).
// --unbonded-max-steps: a lower cap of the conventional settling before
// bonding (its unbonded packing creeps towards the ratio slowly: the bonds
// then stop it, and the body still ends at the ratio; see the doc). --porosity: the conventional
// expansion's target (default the PCRM body's porosity; in rigid walls that
// jams, see the doc). --pcrm-only: the PCRM route alone.
// --require-equilibrium: exit 1 unless both routes' final bodies reached the
// ratio and their profile errors are finite.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/common/command_line.hpp"
#include "dfc/common/version.hpp"
#include "dfc/dem/conventional_generation.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/model_builder.hpp"
#include "dfc/dem/model_layout.hpp"
#include "dfc/dem/particle_stress.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/settling.hpp"

namespace {

using namespace dfc::dem;
using nlohmann::json;

struct Options {
  std::string scenario;
  double radius = 0.0;  ///< m; 0: the scenario's
  double height = 0.0;  ///< m; 0: the scenario's
  int sides = 48;
  double ratio = 0.002;
  std::int64_t max_steps = 2000000;
  std::int64_t unbonded_max_steps = 0;  ///< cap of the conventional settling before bonding; 0: max_steps
  int threads = 1;
  double porosity = 0.0;  ///< conventional target; 0: the PCRM body's
  bool require_equilibrium = false;
  bool pcrm_only = false;  ///< the conventional route is skipped (a domain too large for it on this machine)
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << "generation_compare --scenario FILE [--radius-m R] [--height-m H] [--sides 48] [--ratio 0.002]\n"
                   "                   [--max-steps 2000000] [--unbonded-max-steps M] [--threads 1] [--porosity N] [--pcrm-only]\n"
                   "                   [--require-equilibrium]\n"
                   "PCRM against conventional generation of the scenario's DEM body at N g in rigid walls\n"
                   "(docs/dem_generation.md); one JSON object per route on stdout.\n";
      std::exit(0);
    }
    if (a == "--version") {
      std::cout << "generation_compare " << dfc::project_version() << "\n";
      std::exit(0);
    }
    if (a == "--pcrm-only") {
      o.pcrm_only = true;
      continue;
    }
    if (a == "--require-equilibrium") {
      o.require_equilibrium = true;
      continue;
    }
    if (i + 1 >= argc) throw std::runtime_error("option " + a + " needs a value");
    const std::string v = argv[++i];
    if (a == "--scenario") o.scenario = v;
    else if (a == "--radius-m") o.radius = dfc::parse_number_option(a, v, dfc::Bounds{0.0, 100.0});
    else if (a == "--height-m") o.height = dfc::parse_number_option(a, v, dfc::Bounds{0.0, 100.0});
    else if (a == "--sides") o.sides = int(dfc::parse_count_option(a, v, 8, 100000));
    else if (a == "--ratio") o.ratio = dfc::parse_number_option(a, v, dfc::kPositive);
    else if (a == "--max-steps") o.max_steps = std::int64_t(dfc::parse_count_option(a, v, 1, std::uint64_t(1) << 62));
    else if (a == "--unbonded-max-steps") o.unbonded_max_steps = std::int64_t(dfc::parse_count_option(a, v, 0, std::uint64_t(1) << 62));
    else if (a == "--threads") o.threads = int(dfc::parse_count_option(a, v, 0, 4096));
    else if (a == "--porosity") o.porosity = dfc::parse_number_option(a, v, dfc::Bounds{0.0, 1.0});
    else throw std::runtime_error("unknown option " + a);
  }
  if (o.scenario.empty()) throw std::runtime_error("--scenario FILE is required");
  if (o.sides < 8) throw std::runtime_error("--sides must be at least 8");
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// s, the CPU time of this process: with one DEM thread the measure that
/// another job on the machine does not inflate (wall time does).
double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

/// The open side wall: `sides` panels inscribed in the circle, in rows about
/// four panel widths high at most; shared vertices share indices.
json side_wall(double radius, double z_min, double z_max, int sides) {
  const double width = 2.0 * radius * std::sin(std::numbers::pi / sides);
  const int rows = std::max(1, int(std::ceil((z_max - z_min) / (4.0 * width))));
  json vertices = json::array(), facets = json::array();
  for (int r = 0; r <= rows; ++r)
    for (int s = 0; s < sides; ++s) {
      const double a = 2.0 * std::numbers::pi * s / sides;
      vertices.push_back({radius * std::cos(a), radius * std::sin(a), z_min + (z_max - z_min) * r / rows});
    }
  for (int r = 0; r < rows; ++r)
    for (int s = 0; s < sides; ++s) {
      const int a = r * sides + s, b = r * sides + (s + 1) % sides;
      facets.push_back({a, b, b + sides});
      facets.push_back({a, b + sides, a + sides});
    }
  return {{"type", "facets"}, {"name", "side"}, {"vertices_m", vertices}, {"facets", facets}};
}

/// The scenario's DEM section for this domain, walls and thread count, with N g.
json dem_section(const Options& o) {
  std::ifstream in(o.scenario);
  if (!in) throw std::runtime_error("cannot read " + o.scenario);
  const json scenario = json::parse(in);
  json dem = scenario.at("participants").at("dem").at("config");
  json& region = dem.at("particles").at("region");
  if (region.at("type") != "cylinder") throw std::runtime_error(o.scenario + ": the DEM region must be a cylinder");
  if (o.radius > 0.0) region["radius_m"] = o.radius;
  if (o.height > 0.0) region["z_max_m"] = region.at("z_min_m").get<double>() + o.height;
  const double radius = region.at("radius_m"), z_min = region.at("z_min_m"), z_max = region.at("z_max_m");
  json walls = json::array();
  for (json wall : dem.value("walls", json::array())) {
    if (wall.value("type", "") == "plane") wall["half_size_m"] = 2.0 * radius;  // covers the floor of any domain size
    walls.push_back(wall);
  }
  walls.push_back(side_wall(radius, z_min, z_max, o.sides));
  dem["walls"] = walls;
  const json& g = scenario.at("gravity");
  dem["gravity_m_s2"] = {0.0, 0.0, -g.at("g_m_s2").get<double>() * g.at("g_level").get<double>()};
  dem["threads"] = o.threads;
  return dem;
}

double rms(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += x * x;
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(s / double(v.size()));
}

double max_abs(const std::vector<double>& v) {
  double m = v.empty() ? std::numeric_limits<double>::quiet_NaN() : 0.0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// The final state of a route: counts, the stress profile against theory
/// (interior slices), porosity and where the weight goes.
json final_state(const Simulation& sim, const BedRegion& region, double slice_height, const StressProfile& theory) {
  const ParticleStore& p = sim.particles();
  const int slices = std::max(3, int(std::lround((region.z_max - region.z_min) / slice_height)));
  const SliceProfile profile = slice_profile(sim, region, slices, 4.0 * largest_radius(p));
  std::vector<double> ev, eh, k, porosity;
  for (std::size_t s = 1; s + 1 < profile.z.size(); ++s) {  // the top and bottom slices are the boundary layers
    const double sv = theory.vertical(profile.z[s]);
    ev.push_back(profile.sigma_v[s] / sv - 1.0);
    eh.push_back(profile.sigma_h[s] / (theory.k0 * sv) - 1.0);
    k.push_back(profile.sigma_h[s] / profile.sigma_v[s]);
    porosity.push_back(profile.porosity[s]);
  }
  const Measurements m = measure(sim);
  const BondCounts bonds = sim.bond_counts();
  double top = -INFINITY;
  std::size_t outside = 0;  // centres out of the region: spheres thrown out of the container
  for (std::size_t i = 0; i < p.size(); ++i) {
    top = std::max(top, p.position[i].z + p.radius[i]);
    if (clearance({p.position[i], 0.0}, region) < 0.0) ++outside;
  }
  json walls = json::object();
  for (const Wall& w : sim.walls()) walls[w.name + "_weight_share"] = -w.force.z / m.total_weight;
  const auto mean = [](const std::vector<double>& v) {
    double s = 0.0;
    for (const double x : v) s += x;
    return v.empty() ? std::numeric_limits<double>::quiet_NaN() : s / double(v.size());
  };
  return {{"spheres", p.size()},
          {"bonds_intact", bonds.intact},
          {"bonds_damaged", bonds.damaged},
          {"bonds_broken", bonds.broken_tension + bonds.broken_shear},
          {"unbalanced_force_ratio", m.unbalanced_force_ratio},
          {"interior_slices", ev.size()},
          {"slice_height_m", (region.z_max - region.z_min) / slices},
          {"sigma_v_error_max", max_abs(ev)},
          {"sigma_v_error_rms", rms(ev)},
          {"sigma_v_error_mean", mean(ev)},
          {"sigma_h_error_max", max_abs(eh)},
          {"sigma_h_error_rms", rms(eh)},
          {"sigma_h_error_mean", mean(eh)},
          {"k_mean", mean(k)},
          {"k_min", *std::min_element(k.begin(), k.end())},
          {"k_max", *std::max_element(k.begin(), k.end())},
          {"porosity_interior", mean(porosity)},
          {"top_m", top},
          {"outside_region", outside},
          {"walls", walls}};
}

json stage(std::int64_t steps, double seconds, std::size_t spheres) {
  return {{"steps", steps}, {"seconds", seconds}, {"particle_steps", double(steps) * double(spheres)}};
}

bool finite_errors(const json& state) {
  return std::isfinite(state.at("sigma_v_error_max").get<double>()) && std::isfinite(state.at("sigma_h_error_max").get<double>());
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  const DemConfig config = parse_dem_config(dem_section(o));
  SettlingTarget target{.unbalanced_force_ratio = o.ratio, .check_every = 10, .min_steps = 200, .max_steps = o.max_steps, .on_check = {}};
  target.on_check = [](std::int64_t steps, double ratio) {  // progress on stderr, every 1 000 steps
    if (steps % 1000 == 0) std::cerr << "  settling: step " << steps << ", unbalanced-force ratio " << ratio << std::endl;
  };
  const PcrmConfig& pcrm = *config.particles.pcrm;
  bool ok = true;

  // (a) PCRM: the model builder's route in the rigid walls, then settling under N g.
  std::cerr << "generation_compare: pcrm" << std::endl;
  double cpu_start = cpu_seconds();
  auto start = std::chrono::steady_clock::now();
  DemModel model = build_model(config);
  const double build_seconds = seconds_since(start);
  Simulation& body = *model.simulation;
  const GeneratedBody& generated = *model.generation;
  start = std::chrono::steady_clock::now();
  const Settling pcrm_settling = settle(body, model.dt, target);
  const double pcrm_settle_seconds = seconds_since(start);
  const double pcrm_cpu_seconds = cpu_seconds() - cpu_start;
  const double slice_height = generated.rev.cell.length().z;
  json pcrm_out = final_state(body, pcrm.region, slice_height, generated.profile);
  const std::size_t n_rev = generated.rev.spheres.size(), n_pcrm = body.particles().size();
  const double fit_seconds = build_seconds - generated.rev_seconds - generated.replication_seconds;
  pcrm_out["route"] = "pcrm";
  pcrm_out["rev_spheres"] = n_rev;
  pcrm_out["rev_porosity"] = generated.rev.porosity;
  pcrm_out["removed_by_walls"] = model.removed_particles;
  pcrm_out["seated"] = generated.seated;
  pcrm_out["dt_s"] = model.dt;
  pcrm_out["reached"] = pcrm_settling.reached;
  pcrm_out["stages"] = {{"rev", stage(generated.rev.steps, generated.rev_seconds, n_rev)},
                        {"replication_and_scaling", stage(0, generated.replication_seconds, 0)},
                        {"trimming_and_seating", stage(0, fit_seconds, 0)},
                        {"settling", stage(pcrm_settling.steps, pcrm_settle_seconds, n_pcrm)}};
  pcrm_out["seconds"] = build_seconds + pcrm_settle_seconds;
  pcrm_out["cpu_seconds"] = pcrm_cpu_seconds;
  pcrm_out["steps"] = generated.rev.steps + pcrm_settling.steps;
  std::cout << pcrm_out.dump() << std::endl;
  ok = ok && pcrm_settling.reached && finite_errors(pcrm_out);
  model.simulation.reset();
  if (o.pcrm_only) return o.require_equilibrium && !ok ? 1 : 0;

  // (b) Conventional: the same radii at the PCRM body's porosity over the
  // polygon's area: placed in the circle of that area, of radius
  // R sqrt(n sin(2 pi/n) / 2 pi), a sphere pokes through the facets by at most
  // that less the polygon's apothem R cos(pi/n), 7e-4 R for n = 48 (a few per
  // cent of the smallest start radius; the expansion's relaxation absorbs it).
  std::cerr << "generation_compare: conventional" << std::endl;
  ConventionalSpec spec;
  spec.particles = pcrm.rev.particles;
  spec.particles.porosity = o.porosity > 0.0 ? o.porosity : generated.rev.porosity;
  spec.region = pcrm.region;
  spec.region.radius = pcrm.region.radius * std::sqrt(o.sides * std::sin(2.0 * std::numbers::pi / o.sides) / (2.0 * std::numbers::pi));
  spec.density = config.particles.density;
  spec.fraction_of_critical = config.timestep.fraction_of_critical;
  spec.settling = target;
  if (o.unbonded_max_steps > 0) spec.settling.max_steps = o.unbonded_max_steps;
  spec.bonded_settling = target;
  spec.relaxation_max_steps = o.max_steps;
  // The relaxation ends when the lid carries 1 % of the self-weight stress at
  // the floor: the stress the expansion stored is then small against the
  // field the body is generated for, and no sphere leaves with the lid.
  spec.relaxed_lid_pressure = 0.01 * generated.profile.vertical(pcrm.region.z_min);
  std::vector<Wall> walls;
  for (const auto& w : lay_out_model(config).walls) walls.push_back(make_wall(w.name, w.mesh, WallMotion::prescribed, w.contact));
  const SimulationSettings settings{.particle_law = config.contact,
                                    .gravity = config.gravity,
                                    .local_damping = config.local_damping,
                                    .skin = config.skin,
                                    .threads = config.threads,
                                    .install_bonds_at_start = false};
  cpu_start = cpu_seconds();
  const ConventionalBody conventional = generate_conventionally(spec, settings, walls);
  const double conventional_cpu_seconds = cpu_seconds() - cpu_start;
  json conv_out = final_state(*conventional.simulation, pcrm.region, slice_height, generated.profile);
  const std::size_t n_conv = conventional.simulation->particles().size();
  conv_out["route"] = "conventional";
  conv_out["target_porosity"] = spec.particles.porosity;
  conv_out["dt_s"] = conventional.dt;
  // reached: the final body is at the ratio (the settling before bonding may
  // stop at its own cap, --unbonded-max-steps; settled_before_bonding says).
  conv_out["reached"] = conventional.relaxation.reached && conventional.bonded_settling.reached;
  conv_out["settled_before_bonding"] = conventional.settling.reached;
  conv_out["ratio_before_bonding"] = conventional.settling.ratio;
  conv_out["lid_pressure_pa"] = conventional.lid_pressure;
  conv_out["relaxed_lid_pressure_pa"] = conventional.relaxed_lid_pressure;
  conv_out["stages"] = {{"expansion", stage(conventional.expansion.steps, conventional.expansion.seconds, n_conv)},
                        {"relaxation", stage(conventional.relaxation.steps, conventional.relaxation.seconds, n_conv)},
                        {"settling", stage(conventional.settling.steps, conventional.settling.seconds, n_conv)},
                        {"bonding_and_settling", stage(conventional.bonded_settling.steps, conventional.bonded_settling.seconds, n_conv)}};
  conv_out["seconds"] = conventional.expansion.seconds + conventional.relaxation.seconds + conventional.settling.seconds + conventional.bonded_settling.seconds;
  conv_out["cpu_seconds"] = conventional_cpu_seconds;
  conv_out["steps"] = conventional.expansion.steps + conventional.relaxation.steps + conventional.settling.steps + conventional.bonded_settling.steps;
  std::cout << conv_out.dump() << std::endl;
  ok = ok && conventional.relaxation.reached && conventional.bonded_settling.reached && finite_errors(conv_out);
  return o.require_equilibrium && !ok ? 1 : 0;
} catch (const std::exception& e) {
  std::cerr << "generation_compare: " << e.what() << "\n";
  return 2;
}
