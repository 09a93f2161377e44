// dem_throughput: time the DEM hot loop on a settled bed (particle-steps/s).
//
//   dem_throughput [--side N] [--layers N] [--threads "1 2"] [--steps N] [--max-settle N]
//
// 1. builds a bed of N x N x layers spheres (r 4.5-5 mm, rho 2650, linear law
//    kn 1e5 N/m, ks kn/4, mu 0.5, beta_n 0.3) in a box with a frictional floor
//    and frictionless sides, and settles it under gravity with local damping
//    0.7 until the unbalanced-force ratio falls below 1e-4 (or --max-settle steps);
// 2. for each thread count, restarts the settled bed and times --steps steps.
// Throughput = particles x steps / wall seconds, the measure of the peer
// benchmark (shared/bench/peers/README.md). This bed is not the peers' packing
// (theirs is periodic in x and y, which this DEM does not have yet): compare
// orders of magnitude, not digits.
#include <chrono>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "dfc/dem/measurements.hpp"
#include "dfc/dem/model_builder.hpp"

namespace {

using namespace dfc::dem;

struct Options {
  int side = 20;
  int layers = 8;
  std::vector<int> threads{1, 2};
  int steps = 2000;
  int max_settle = 400000;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--side") o.side = std::stoi(v);
    else if (a == "--layers") o.layers = std::stoi(v);
    else if (a == "--steps") o.steps = std::stoi(v);
    else if (a == "--max-settle") o.max_settle = std::stoi(v);
    else if (a == "--threads") {
      o.threads.clear();
      std::istringstream list(v);
      for (int t = 0; list >> t;) o.threads.push_back(t);
    } else throw std::runtime_error("unknown option " + a);
  }
  return o;
}

nlohmann::json bed(const Options& o, int threads) {
  const double pitch = 2 * 0.005 * 1.05, side = o.side * pitch, height = o.layers * pitch;
  const nlohmann::json smooth = {{"kn_n_m", 1e5}, {"ks_n_m", 2.5e4}, {"friction", 0.0}, {"damping_ratio_normal", 0.3}};
  nlohmann::json walls = nlohmann::json::array({{{"type", "plane"}, {"name", "floor"}, {"point_m", {0.5 * side, 0.5 * side, 0}}, {"normal", {0, 0, 1}}}});
  for (const auto& [point, normal] : {std::pair<std::vector<double>, std::vector<double>>{{0, 0.5 * side, 0}, {1, 0, 0}},
                                      {{side, 0.5 * side, 0}, {-1, 0, 0}}, {{0.5 * side, 0, 0}, {0, 1, 0}}, {{0.5 * side, side, 0}, {0, -1, 0}}})
    walls.push_back({{"type", "plane"}, {"point_m", point}, {"normal", normal}, {"contact", smooth}});
  return {{"particles",
           {{"generator", "lattice"},
            {"region", {{"type", "box"}, {"min_m", {0, 0, 0}}, {"max_m", {side, side, height}}}},
            {"radius_min_m", 0.0045},
            {"radius_max_m", 0.005},
            {"density_kg_m3", 2650}}},
          {"contact", {{"kn_n_m", 1e5}, {"ks_n_m", 2.5e4}, {"friction", 0.5}, {"damping_ratio_normal", 0.3}}},
          {"timestep", {{"fraction_of_critical", 0.3}}},
          {"gravity_m_s2", {0, 0, -9.81}},
          {"walls", walls},
          {"threads", threads}};
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  // 1. Settle.
  DemModel model = build_model(parse_dem_config(bed(o, 0)));
  Simulation& settling = *model.simulation;
  std::int64_t settle_steps = 0;
  double ratio = 1.0;
  while (settle_steps < o.max_settle && ratio > 1e-4) {
    settling.run(5000, model.dt);
    settle_steps += 5000;
    ratio = measure(settling).unbalanced_force_ratio;
  }
  const Measurements settled = measure(settling);
  std::cout << settled.particle_count << " particles settled in " << settle_steps << " steps: unbalanced force ratio " << ratio
            << ", coordination number " << settled.coordination_number << ", candidate pairs per particle "
            << double(settling.pair_contacts().size()) / double(settled.particle_count) << "\n";

  // 2. Time each thread count from the same settled state.
  for (const int threads : o.threads) {
    DemModel timed = build_model(parse_dem_config(bed(o, threads)));
    Simulation& sim = *timed.simulation;
    ParticleStore& p = sim.particles_for_edit();
    p = settling.particles();  // settled positions and velocities (contact history restarts)
    sim.run(200, model.dt);    // rebuild the lists, reload the shear springs
    const std::size_t rebuilds = sim.rebuild_count();
    const auto t0 = std::chrono::steady_clock::now();
    sim.run(o.steps, model.dt);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << "threads " << sim.threads() << ": " << double(p.size()) * o.steps / seconds << " particle-steps/s (" << seconds << " s for "
              << o.steps << " steps, " << sim.rebuild_count() - rebuilds << " rebuilds)\n";
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "dem_throughput: " << e.what() << "\n";
  return 1;
}
