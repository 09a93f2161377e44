// The open-ended pile jacked into chalk (docs/open_pile.md; Ciantia,
// Previtali, Zheng et al. 2024, §3-4) through the real coupler, DEM and FDM
// servers: the small variant tests/e2e/scenarios/open_pile_small.json (S = 8
// at the pile, 16 beyond, the pile pushed 3 mm at 2 m/s), run once for all
// checks (one process, tests/e2e/CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

constexpr double kDiameter = 0.008;     ///< m, the pile's outer diameter
constexpr double kInnerRadius = 0.003;  ///< m, the bore (wall 1 mm)
constexpr double kSurface = 0.020;      ///< m, the region's top, where the tip starts
constexpr double kCore = 0.010;         ///< m, the DEM core's radius

const std::filesystem::path& results() {
  static const std::filesystem::path file = [] {
    auto folder = fresh_directory("open_pile_small");
    const CommandResult result =
        run_command({coupler(), "run", (e2e_dir() / "scenarios" / "open_pile_small.json").string(), "--out", folder.string(), "--no-progress"},
                    std::chrono::seconds(900));
    EXPECT_EQ(result.exit_status, 0) << result.output;
    return folder / "p1" / "results.h5";
  }();
  return file;
}

double final_tip_z() { return kSurface - series(results(), "dem_pile_displacement_m").back(); }

TEST(OpenPile, TheForceSplitsExactlyIntoAnnulusInnerAndOuterShaft) {
  const auto total = series(results(), "dem_pile_force_n");
  const auto annulus = series(results(), "dem_pile_tip_force_n");
  const auto inner = series(results(), "dem_pile_inner_shaft_force_n");
  const auto outer = series(results(), "dem_pile_outer_shaft_force_n");
  // Each part is summed over its own facets, the total over the wall's
  // contacts: the same contact forces in two orders, equal to a few roundings.
  for (std::size_t k = 0; k < total.size(); ++k)
    ASSERT_NEAR(annulus[k] + inner[k] + outer[k], total[k], 1e-12 * (1.0 + std::abs(annulus[k]) + std::abs(inner[k]) + std::abs(outer[k])))
        << "record " << k;
  // The flat annulus carries most of a bonded rock's resistance (it crushes
  // the chalk beneath it): over the loading its mean exceeds half the total.
  const auto moved = series(results(), "dem_pile_displacement_m");
  double on_annulus = 0.0, on_pile = 0.0;
  for (std::size_t k = 0; k < total.size(); ++k)
    if (moved[k] > 0.0) on_annulus += annulus[k], on_pile += total[k];
  std::cout << "mean share of the annulus over the loading " << on_annulus / on_pile << "\n";
  EXPECT_GT(on_annulus, 0.5 * on_pile);
}

TEST(OpenPile, SoilEntersThePile) {
  // The tip starts on the surface with nothing in its bore; after 3 mm the
  // bore holds a column of particles. Its length L is at least half the
  // penetration (a column that enters at half the pile's rate would be
  // strongly plugged already) and not more than the penetration plus two
  // largest fine diameters (1.44 mm each: the surface's roughness, heave).
  const auto particles = series(results(), "dem_pile_plug_particles");
  const auto length = series(results(), "dem_pile_plug_length_m");
  const auto moved = series(results(), "dem_pile_displacement_m");
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

TEST(OpenPile, RadialStressRisesTowardsTheWallNearTheTip) {
  // At the end, within D/2 of the tip's depth: the ring 2 mm wide against
  // the pile's outer wall against the next ring out (2 mm wide, to 1 mm
  // short of the coupling wall). The jacked pile pushes the rock aside.
  // D/2, not D/4: the outer ring holds about 50 spheres within D/2 against
  // 30 within D/4, and a crushing event under the annulus can unload the
  // inner ring at the last record: within D/4 it read 69 against 83 kPa once
  // in 8 runs of this variant (REV seeds 5, 1, 11; two FDM meshes; 2 and
  // 0.5 m/s; FDM damping 0.8 and 0.2); within D/2 the inner ring read 1.8-3.1
  // times the outer in all 8.
  const h5::File file = h5::File::open_read_only(results());
  const std::string snap = last_snapshot(file, "dem");
  const double tip = final_tip_z();
  const double r0 = 0.5 * kDiameter;
  const double near = ring_sigma_rr(file, snap, r0, r0 + 0.002, tip - 0.5 * kDiameter, tip + 0.5 * kDiameter);
  const double far = ring_sigma_rr(file, snap, r0 + 0.003, r0 + 0.005, tip - 0.5 * kDiameter, tip + 0.5 * kDiameter);
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

TEST(OpenPile, DemAndFdmRadialStressesAgreeAtTheCouplingWall) {
  // At the end, over the band within 1 D of the tip's depth (cut at the
  // surface): the DEM's radial stress at the coupling wall is the traction its
  // particles put on the wall; the FDM's is its stress field carried to the
  // wall from its first two rings of zones (fdm_sigma_rr_at). They agree
  // within 10 % (the issue). Measured on this variant (FDM first ring 0.54 mm
  // wide, 2 mm layers) with REV seeds 5, 1 and 11: 0.99, 0.95, 0.98; the first
  // ring's own mean 0.93, 0.91, 0.95 (centred 0.27 mm out). With the earlier
  // mesh (first ring 3.1 mm, 4 mm layers) the first ring read 0.68-0.75 and
  // the fitted form 0.88-0.96: the gap was the first zone's size. The D/4
  // band is not asserted: it holds two layers of zones and a few grains.
  const h5::File file = h5::File::open_read_only(results());
  const std::string snap = last_snapshot(file, "continuum");
  const double tip = final_tip_z();
  const double z_lo = tip - kDiameter, z_hi = std::min(tip + kDiameter, kSurface);
  const double traction = wall_traction(file, snap, kCore, z_lo, z_hi);
  const FdmWallStress fdm = fdm_sigma_rr_at(file, snap, kCore, z_lo, z_hi);
  std::cout << "within 1 D of the tip's depth: radial traction on the coupling wall " << traction << " Pa; the FDM's first ring "
            << fdm.first_ring << " Pa (" << fdm.first_ring / traction << "), carried to the wall " << fdm.at_wall << " Pa ("
            << fdm.at_wall / traction << ")\n";
  ASSERT_GT(traction, 0.0);
  EXPECT_NEAR(fdm.at_wall / traction, 1.0, 0.10);
}

TEST(OpenPile, DamageConcentratesBelowTheAnnulus) {
  // Mean bond damage D (1 = broken) of the bonds beneath the annulus (r
  // within 0.5 mm of the wall's span, down to D/2 below the tip) against the
  // far field (the outermost 2 mm of the core, deeper than 1 D below the
  // tip). Factor 3: the far field's D is the REV's few damaged bonds.
  const h5::File file = h5::File::open_read_only(results());
  const std::string snap = last_snapshot(file, "dem");
  const auto where = h5::read_f64(file, snap + "/bond_position");
  const auto damage = h5::read_f64(file, snap + "/bond_damage");
  const double tip = final_tip_z();
  double below = 0.0, far = 0.0;
  int below_n = 0, far_n = 0;
  for (std::size_t b = 0; b < damage.size(); ++b) {
    const double r = std::hypot(where[3 * b], where[3 * b + 1]), z = where[3 * b + 2];
    if (r >= kInnerRadius - 0.0005 && r <= 0.5 * kDiameter + 0.0005 && z < tip && z >= tip - 0.5 * kDiameter) {
      below += damage[b];
      ++below_n;
    } else if (r >= kCore - 0.002 && z < tip - kDiameter) {
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

TEST(OpenPile, VerticalForcesOnTheParticlesBalanceTheirMomentumChange) {
  // The particles' vertical momentum balance (SPEC.md §6.3) per exchange:
  //   dP/dt = -pile - floor + coupling wall (the FDM) - weight + local damping.
  // Every term is an average over the same steps, so the balance closes to
  // round-off (1e-6 of pile force + weight leaves decades). At the
  // generation's equilibrium, just before the pile moves, the boundaries
  // alone carry the weight within 1 %. Under loading the damping force is
  // the part of the resistance no boundary carries: reported (the share
  // docs/open_pile.md §4 discusses), not asserted.
  const auto pile = series(results(), "dem_wall_pile_force_n");
  const auto floor = series(results(), "dem_wall_floor_force_n");
  const auto interface = series(results(), "dem_interface_force_reaction");
  const auto weight = series(results(), "dem_total_weight_n");
  const auto damping = series(results(), "dem_damping_force_n");
  const auto momentum = series(results(), "dem_particle_momentum_n_s");
  const auto time = series(results(), "time_s");
  const auto moved = series(results(), "dem_pile_displacement_m");
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

}  // namespace
}  // namespace dfc::testing
