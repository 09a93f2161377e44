// The open-ended pile jacked into chalk (docs/open_pile.md; Ciantia,
// Previtali, Zheng et al. 2024, §3-4) through the real coupler, DEM and FDM
// servers, each model run once for all its checks (one process,
// tests/e2e/CMakeLists.txt):
//  - OpenPile: the small variant tests/e2e/scenarios/open_pile_small.json
//    (S = 8 at the pile, 16 beyond, the pile pushed 3 mm at 2 m/s), label e2e;
//  - OpenPileReduced: packing p2 of scenarios/open_pile_chalk_reduced.json
//    (tests/e2e/scenarios/open_pile_reduced_p2.json: 20 mm at 1 m/s, about
//    25 min), label slow; with DFC_OPEN_PILE_REDUCED_RESULTS=FILE it checks
//    that results file (a run of ./vc run) instead of running the model.
// The geometry (pile, core, surface) comes from the run's own scenario.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

/// One open-pile run under test: its results file and the geometry its scenario gave.
struct PileRun {
  std::filesystem::path results;
  double diameter = 0.0;      ///< m, the pile's outer diameter
  double inner_radius = 0.0;  ///< m, the bore
  double surface = 0.0;       ///< m, the DEM region's top, where the tip starts
  double core = 0.0;          ///< m, the DEM core's radius (the coupling wall)
  [[nodiscard]] double final_tip_z() const { return surface - series(results, "dem_pile_displacement_m").back(); }
};

PileRun read_run(const std::filesystem::path& results) {
  std::ifstream in(results.parent_path() / "scenario.json");
  const auto scenario = nlohmann::json::parse(in);
  const auto& dem = scenario.at("participants").at("dem").at("config");
  const auto& pile = dem.at("pile");
  const auto& region = dem.at("particles").at("region");
  PileRun run;
  run.results = results;
  run.diameter = 2.0 * pile.at("radius_m").get<double>();
  run.inner_radius = pile.at("radius_m").get<double>() - pile.at("wall_thickness_m").get<double>();
  run.surface = region.at("z_max_m").get<double>();
  run.core = region.at("radius_m").get<double>();
  return run;
}

/// Runs `scenario` (one variant, `label`) into a fresh folder and returns its run.
PileRun run_scenario(const std::string& folder_name, const std::filesystem::path& scenario, const std::string& label, int limit_s) {
  auto folder = fresh_directory(folder_name);
  const CommandResult result =
      run_command({coupler(), "run", scenario.string(), "--out", folder.string(), "--no-progress"}, std::chrono::seconds(limit_s));
  EXPECT_EQ(result.exit_status, 0) << result.output;
  return read_run(folder / label / "results.h5");
}

const PileRun& small_run() {
  static const PileRun run = run_scenario("open_pile_small", e2e_dir() / "scenarios" / "open_pile_small.json", "p1", 900);
  return run;
}

const PileRun& reduced_run() {
  static const PileRun run = [] {
    if (const char* given = std::getenv("DFC_OPEN_PILE_REDUCED_RESULTS"); given != nullptr && *given != '\0') return read_run(given);
    return run_scenario("open_pile_reduced_p2", e2e_dir() / "scenarios" / "open_pile_reduced_p2.json", "p2", 5400);
  }();
  return run;
}

void check_force_split(const PileRun& run) {
  const auto total = series(run.results, "dem_pile_force_n");
  const auto annulus = series(run.results, "dem_pile_tip_force_n");
  const auto inner = series(run.results, "dem_pile_inner_shaft_force_n");
  const auto outer = series(run.results, "dem_pile_outer_shaft_force_n");
  // Each part is summed over its own facets, the total over the wall's
  // contacts: the same contact forces in two orders, equal to a few roundings.
  for (std::size_t k = 0; k < total.size(); ++k)
    ASSERT_NEAR(annulus[k] + inner[k] + outer[k], total[k], 1e-12 * (1.0 + std::abs(annulus[k]) + std::abs(inner[k]) + std::abs(outer[k])))
        << "record " << k;
  // The flat annulus carries most of a bonded rock's resistance (it crushes
  // the chalk beneath it): over the loading its mean exceeds half the total.
  const auto moved = series(run.results, "dem_pile_displacement_m");
  double on_annulus = 0.0, on_pile = 0.0;
  for (std::size_t k = 0; k < total.size(); ++k)
    if (moved[k] > 0.0) on_annulus += annulus[k], on_pile += total[k];
  std::cout << "mean share of the annulus over the loading " << on_annulus / on_pile << "\n";
  EXPECT_GT(on_annulus, 0.5 * on_pile);
}

void check_soil_enters(const PileRun& run) {
  // The tip starts on the surface with nothing in its bore; at the end the
  // bore holds a column of particles. Its length L is at least half the
  // penetration (a column that enters at half the pile's rate would be
  // strongly plugged already) and not more than the penetration plus two
  // largest fine diameters (1.44 mm each: the surface's roughness, heave).
  const auto particles = series(run.results, "dem_pile_plug_particles");
  const auto length = series(run.results, "dem_pile_plug_length_m");
  const auto moved = series(run.results, "dem_pile_displacement_m");
  EXPECT_EQ(particles.front(), 0.0);
  EXPECT_GT(particles.back(), 10.0);
  std::cout << "after " << moved.back() << " m: " << particles.back() << " particles in the bore, column " << length.back() << " m\n";
  EXPECT_GT(length.back(), 0.5 * moved.back());
  EXPECT_LT(length.back(), moved.back() + 2 * 1.44e-3);
}

/// Love–Weber sigma_rr (compression positive) of the particles whose centres
/// lie in the ring r_lo <= r < r_hi between z_lo and z_hi: sum V_p sigma_p,rr
/// over the ring's volume (as tools/centrifuge_foundation.py stress_grid).
double ring_sigma_rr(const h5::File& file, const std::string& snap, double r_lo, double r_hi, double z_lo, double z_hi) {
  const auto x = h5::read_f64(file, snap + "/particle_position");
  const auto radius = h5::read_f64(file, snap + "/particle_radius");
  const auto s = h5::read_f64(file, snap + "/particle_stress_pa");  // xx, xy, xz, yy, yz, zz
  double sum = 0.0;
  for (std::size_t p = 0; p < radius.size(); ++p) {
    const double px = x[3 * p], py = x[3 * p + 1], pz = x[3 * p + 2], r = std::hypot(px, py);
    if (r < r_lo || r >= r_hi || pz < z_lo || pz >= z_hi || r == 0.0) continue;
    const double c = px / r, sn = py / r;
    const double rr = c * c * s[6 * p] + 2 * c * sn * s[6 * p + 1] + sn * sn * s[6 * p + 3];
    sum += 4.0 / 3.0 * M_PI * std::pow(radius[p], 3) * rr;
  }
  return sum / (M_PI * (r_hi * r_hi - r_lo * r_lo) * (z_hi - z_lo));
}

void check_radial_stress_rises(const PileRun& run) {
  // At the end, within D/2 of the tip's depth: the ring 2 mm wide against
  // the pile's outer wall against the next ring out (3-5 mm from the wall,
  // inside the core in both variants). The jacked pile pushes the rock aside.
  // D/2, not D/4: the outer ring holds about 50 spheres within D/2 against
  // 30 within D/4, and a crushing event under the annulus can unload the
  // inner ring at the last record: within D/4 it read 69 against 83 kPa once
  // in 8 runs of this variant (REV seeds 5, 1, 11; two FDM meshes; 2 and
  // 0.5 m/s; FDM damping 0.8 and 0.2); within D/2 the inner ring read 1.8-3.1
  // times the outer in all 8.
  const h5::File file = h5::File::open_read_only(run.results);
  const std::string snap = last_snapshot(file, "dem");
  const double tip = run.final_tip_z();
  const double r0 = 0.5 * run.diameter;
  const double near = ring_sigma_rr(file, snap, r0, r0 + 0.002, tip - 0.5 * run.diameter, tip + 0.5 * run.diameter);
  const double far = ring_sigma_rr(file, snap, r0 + 0.003, r0 + 0.005, tip - 0.5 * run.diameter, tip + 0.5 * run.diameter);
  std::cout << "sigma_rr at the tip's depth: " << near << " Pa next to the wall, " << far << " Pa 3-5 mm out\n";
  EXPECT_GT(near, far);
  EXPECT_GT(near, 0.0);
}

/// The FDM's sigma_rr (compression positive) at radius `at`, from the means
/// of its two innermost rings of zones whose centres lie between z_lo and
/// z_hi: the axisymmetric elastic form sigma_rr = A + B / r^2 (Lame's thick
/// cylinder; Timoshenko & Goodier 1970, docs/theory/fdm.md §2(b)) fitted to
/// the two means as ring averages (the average of 1/r^2
/// over the ring r0..r1 is 2 ln(r1/r0) / (r1^2 - r0^2)). The zone centres lie
/// half a zone outside the wall, where a stress that decays outwards is
/// already lower; the form carries each ring's mean to the wall.
struct FdmWallStress {
  double first_ring = 0.0;  ///< Pa, the innermost ring's mean
  double at_wall = 0.0;     ///< Pa, the fitted form at `at`
};
FdmWallStress fdm_sigma_rr_at(const h5::File& file, const std::string& snap, double at, double z_lo, double z_hi) {
  const auto node = h5::read_f64(file, snap + "/node_position");
  const auto zone_nodes = h5::read_i64(file, snap + "/zone_nodes");
  const auto stress = h5::read_f64(file, snap + "/zone_stress");  // xx, xy, xz, yy, yz, zz; tension positive
  const std::size_t per_zone = zone_nodes.size() / (stress.size() / 6);
  std::vector<double> radii;
  for (std::size_t n = 0; n < node.size() / 3; ++n) radii.push_back(std::hypot(node[3 * n], node[3 * n + 1]));
  std::sort(radii.begin(), radii.end());
  std::vector<double> edges;  // the mesh's rings of nodes (1e-9 m apart at least: the generator's rounding)
  for (const double r : radii)
    if (edges.empty() || r - edges.back() > 1e-9) edges.push_back(r);
  EXPECT_NEAR(edges.front(), at, 1e-9) << "the innermost nodes are the coupling wall";
  double sum[2] = {0.0, 0.0};
  int count[2] = {0, 0};
  for (std::size_t z = 0; z < stress.size() / 6; ++z) {
    double c[3] = {0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < per_zone; ++k)
      for (int d = 0; d < 3; ++d) c[d] += node[3 * std::size_t(zone_nodes[z * per_zone + k]) + d] / double(per_zone);
    const double r = std::hypot(c[0], c[1]);
    if (c[2] < z_lo || c[2] > z_hi) continue;
    for (int ring = 0; ring < 2; ++ring)
      if (r > edges[ring] && r < edges[ring + 1]) {
        const double cs = c[0] / r, sn = c[1] / r;
        sum[ring] += -(cs * cs * stress[6 * z] + 2 * cs * sn * stress[6 * z + 1] + sn * sn * stress[6 * z + 3]);
        ++count[ring];
      }
  }
  EXPECT_GT(count[0], 0);
  EXPECT_GT(count[1], 0);
  const double mean[2] = {sum[0] / count[0], sum[1] / count[1]};
  const auto inverse_square_average = [&](int ring) {
    return 2.0 * std::log(edges[ring + 1] / edges[ring]) / (edges[ring + 1] * edges[ring + 1] - edges[ring] * edges[ring]);
  };
  const double b = (mean[0] - mean[1]) / (inverse_square_average(0) - inverse_square_average(1));
  const double a = mean[0] - b * inverse_square_average(0);
  return {mean[0], a + b / (at * at)};
}

/// The radial traction (compression positive) the particles put on the
/// coupling wall between z_lo and z_hi: the coupling forces on the FDM's wall
/// nodes there (which equal the particles' contact forces on the wall to
/// round-off, the interface balance of every exchange) over the wall area
/// those nodes carry (each layer of nodes the height between the midpoints to
/// its neighbours, cut at the mesh's top and bottom).
double wall_traction(const h5::File& file, const std::string& snap, double radius, double z_lo, double z_hi) {
  const auto node = h5::read_f64(file, snap + "/node_position");
  const auto force = h5::read_f64(file, snap + "/node_external_force");
  std::vector<double> layers;
  for (std::size_t n = 0; n < node.size() / 3; ++n)
    if (std::abs(std::hypot(node[3 * n], node[3 * n + 1]) - radius) < 1e-9) layers.push_back(node[3 * n + 2]);
  std::sort(layers.begin(), layers.end());
  layers.erase(std::unique(layers.begin(), layers.end(), [](double p, double q) { return std::abs(p - q) < 1e-9; }), layers.end());
  double radial = 0.0, height = 0.0;
  for (std::size_t k = 0; k < layers.size(); ++k) {
    if (layers[k] < z_lo || layers[k] > z_hi) continue;
    const double below = k == 0 ? layers[k] : 0.5 * (layers[k] + layers[k - 1]);
    const double above = k + 1 == layers.size() ? layers[k] : 0.5 * (layers[k] + layers[k + 1]);
    height += above - below;
    for (std::size_t n = 0; n < node.size() / 3; ++n) {
      const double x = node[3 * n], y = node[3 * n + 1], r = std::hypot(x, y);
      if (std::abs(r - radius) < 1e-9 && std::abs(node[3 * n + 2] - layers[k]) < 1e-9) radial += (x * force[3 * n] + y * force[3 * n + 1]) / r;
    }
  }
  EXPECT_GT(height, 0.0);
  return radial / (2.0 * M_PI * radius * height);
}

void check_dem_and_fdm_agree(const PileRun& run) {
  // At the end, over the band within 1 D of the tip's depth (cut at the
  // surface): the DEM's radial stress at the coupling wall is the traction its
  // particles put on the wall; the FDM's is its stress field carried to the
  // wall from its first two rings of zones (fdm_sigma_rr_at). They agree
  // within 10 % (the issue). Measured on the small variant (FDM first ring
  // 0.54 mm wide, 2 mm layers) with REV seeds 5, 1 and 11: 0.99, 0.95, 0.98;
  // the first ring's own mean 0.93, 0.91, 0.95 (centred 0.27 mm out). With the earlier
  // mesh (first ring 3.1 mm, 4 mm layers) the first ring read 0.68-0.75 and
  // the fitted form 0.88-0.96: the gap was the first zone's size. The D/4
  // band is not asserted: it holds two layers of zones and a few grains.
  const h5::File file = h5::File::open_read_only(run.results);
  const std::string snap = last_snapshot(file, "continuum");
  const double tip = run.final_tip_z();
  const double z_lo = tip - run.diameter, z_hi = std::min(tip + run.diameter, run.surface);
  const double traction = wall_traction(file, snap, run.core, z_lo, z_hi);
  const FdmWallStress fdm = fdm_sigma_rr_at(file, snap, run.core, z_lo, z_hi);
  std::cout << "within 1 D of the tip's depth: radial traction on the coupling wall " << traction << " Pa; the FDM's first ring "
            << fdm.first_ring << " Pa (" << fdm.first_ring / traction << "), carried to the wall " << fdm.at_wall << " Pa ("
            << fdm.at_wall / traction << ")\n";
  ASSERT_GT(traction, 0.0);
  EXPECT_NEAR(fdm.at_wall / traction, 1.0, 0.10);
}

/// The soil column's length L at penetration h, interpolated between records
/// (the tip starts on the surface, so the travel is the penetration).
double plug_length_at(const PileRun& run, double h) {
  const auto length = series(run.results, "dem_pile_plug_length_m");
  const auto moved = series(run.results, "dem_pile_displacement_m");
  const auto after = std::size_t(std::lower_bound(moved.begin(), moved.end(), h) - moved.begin());
  if (after == 0 || after >= moved.size()) return std::nan("");
  const double w = (h - moved[after - 1]) / (moved[after] - moved[after - 1]);
  return length[after - 1] + w * (length[after] - length[after - 1]);
}

void check_plug_forms(const PileRun& run) {
  // The incremental filling ratio over the last 5 mm, IFR = dL/dh, is below
  // 1: the column grows more slowly than the pile advances (the crushed chalk
  // in the bore compacts and the column's friction on the inner shaft holds
  // it back), and above 0: the pile still cores. 5 mm (0.6 D, about four
  // fine diameters) from 15 mm on: the column's top is known to about half a
  // layer (docs/open_pile.md §2), so an IFR over 5 mm is good to about
  // +-0.1; from 15 mm on the column is more than 10 fine diameters long.
  // Measured at 1 m/s on packing p2 (seed 7): 0.89, PLR 0.90 at 20 mm (0.96
  // and 0.93 on seeds 7 and 1 with the earlier FDM mesh).
  const double end = series(run.results, "dem_pile_displacement_m").back();
  ASSERT_GE(end, 0.02 - 1e-6) << "the run did not reach 20 mm";
  const double before = plug_length_at(run, 0.015), after = plug_length_at(run, 0.02 - 1e-6);
  const double ifr = (after - before) / (0.005 - 1e-6);
  std::cout << "plug: L = " << before << " m at 15 mm, " << after << " m at 20 mm: IFR over the last 5 mm " << ifr
            << ", PLR at 20 mm " << after / 0.02 << "\n";
  EXPECT_LT(ifr, 1.0);
  EXPECT_GT(ifr, 0.0);
}

void check_damage_below_annulus(const PileRun& run) {
  // Mean bond damage D (1 = broken) of the bonds beneath the annulus (r
  // within 0.5 mm of the wall's span, down to D/2 below the tip) against the
  // far field (the outermost 2 mm of the core, deeper than 1 D below the
  // tip). Factor 3: the far field's D is the REV's few damaged bonds.
  const h5::File file = h5::File::open_read_only(run.results);
  const std::string snap = last_snapshot(file, "dem");
  const auto where = h5::read_f64(file, snap + "/bond_position");
  const auto damage = h5::read_f64(file, snap + "/bond_damage");
  const double tip = run.final_tip_z();
  double below = 0.0, far = 0.0;
  int below_n = 0, far_n = 0;
  for (std::size_t b = 0; b < damage.size(); ++b) {
    const double r = std::hypot(where[3 * b], where[3 * b + 1]), z = where[3 * b + 2];
    if (r >= run.inner_radius - 0.0005 && r <= 0.5 * run.diameter + 0.0005 && z < tip && z >= tip - 0.5 * run.diameter) {
      below += damage[b];
      ++below_n;
    } else if (r >= run.core - 0.002 && z < tip - run.diameter) {
      far += damage[b];
      ++far_n;
    }
  }
  ASSERT_GT(below_n, 10);
  ASSERT_GT(far_n, 50);
  std::cout << "mean bond damage beneath the annulus " << below / below_n << " (" << below_n << " bonds), far field " << far / far_n << " ("
            << far_n << ")\n";
  EXPECT_GT(below / below_n, 3.0 * far / far_n);
}

void check_momentum_balance(const PileRun& run) {
  // The particles' vertical momentum balance (SPEC.md §6.3) per exchange:
  //   dP/dt = -pile - floor + coupling wall (the FDM) - weight + local damping.
  // Every term is an average over the same steps, so the balance closes to
  // round-off (1e-6 of pile force + weight leaves decades). At the
  // generation's equilibrium, just before the pile moves, the boundaries
  // alone carry the weight within 1 %. Under loading the damping force is
  // the part of the resistance no boundary carries: reported (the share
  // docs/open_pile.md §4 discusses), not asserted.
  const auto pile = series(run.results, "dem_wall_pile_force_n");
  const auto floor = series(run.results, "dem_wall_floor_force_n");
  const auto interface = series(run.results, "dem_interface_force_reaction");
  const auto weight = series(run.results, "dem_total_weight_n");
  const auto damping = series(run.results, "dem_damping_force_n");
  const auto momentum = series(run.results, "dem_particle_momentum_n_s");
  const auto time = series(run.results, "time_s");
  const auto moved = series(run.results, "dem_pile_displacement_m");
  const auto boundaries = [&](std::size_t k) { return -pile[3 * k + 2] - floor[3 * k + 2] + interface[3 * k + 2] - weight[k]; };
  const auto first = std::size_t(std::find_if(moved.begin(), moved.end(), [](double d) { return d > 0.0; }) - moved.begin());
  ASSERT_GT(first, 1u);
  EXPECT_LT(std::abs(boundaries(first - 1)), 0.01 * weight[first - 1]);
  double worst = 0.0, damping_sum = 0.0, load = 0.0;
  for (std::size_t k = 1; k < moved.size(); ++k) {
    const double rate = (momentum[3 * k + 2] - momentum[3 * (k - 1) + 2]) / (time[k] - time[k - 1]);
    const double scale = std::abs(pile[3 * k + 2]) + weight[k];
    worst = std::max(worst, std::abs(rate - boundaries(k) - damping[3 * k + 2]) / scale);
    if (k >= first) {
      damping_sum += damping[3 * k + 2];
      load += std::abs(pile[3 * k + 2]);
    }
  }
  EXPECT_LT(worst, 1e-6);
  std::cout << "momentum balance closes to " << worst << " of pile force + weight; under loading the local damping force is "
            << damping_sum / load << " of the pile force\n";
}

// The small variant (label e2e): 3 mm, every check that holds from the start.
TEST(OpenPile, TheForceSplitsExactlyIntoAnnulusInnerAndOuterShaft) { check_force_split(small_run()); }
TEST(OpenPile, SoilEntersThePile) { check_soil_enters(small_run()); }
TEST(OpenPile, RadialStressRisesTowardsTheWallNearTheTip) { check_radial_stress_rises(small_run()); }
TEST(OpenPile, DemAndFdmRadialStressesAgreeAtTheCouplingWall) { check_dem_and_fdm_agree(small_run()); }
TEST(OpenPile, DamageConcentratesBelowTheAnnulus) { check_damage_below_annulus(small_run()); }
TEST(OpenPile, VerticalForcesOnTheParticlesBalanceTheirMomentumChange) { check_momentum_balance(small_run()); }

// The reduced model to 20 mm (label slow): the same checks at the end of
// installation, and the plug.
TEST(OpenPileReduced, TheForceSplitsExactlyIntoAnnulusInnerAndOuterShaft) { check_force_split(reduced_run()); }
TEST(OpenPileReduced, SoilEntersThePile) { check_soil_enters(reduced_run()); }
TEST(OpenPileReduced, ThePlugFormsTheIncrementalFillingRatioFallsBelowOne) { check_plug_forms(reduced_run()); }
TEST(OpenPileReduced, RadialStressRisesTowardsTheWallNearTheTip) { check_radial_stress_rises(reduced_run()); }
TEST(OpenPileReduced, DemAndFdmRadialStressesAgreeAtTheCouplingWall) { check_dem_and_fdm_agree(reduced_run()); }
TEST(OpenPileReduced, DamageConcentratesBelowTheAnnulus) { check_damage_below_annulus(reduced_run()); }
TEST(OpenPileReduced, VerticalForcesOnTheParticlesBalanceTheirMomentumChange) { check_momentum_balance(reduced_run()); }

}  // namespace
}  // namespace dfc::testing
