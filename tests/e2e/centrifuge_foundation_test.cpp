// The virtual centrifuge experiment (docs/centrifuge_foundation.md; Zheng,
// Previtali, Ciantia et al. 2023, Fig. 5-7) through the real coupler, DEM and
// FDM servers. The fast checks run the small variant
// (tests/e2e/scenarios/centrifuge_pile_small.json: 100 g, packing 1, pushed
// 6 mm, twice); the g-level check runs the study's 1 g and 100 g runs
// (centrifuge_pile_glevels.json, ctest label slow). One process runs each
// group (tests/e2e/CMakeLists.txt), so each scenario runs once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

constexpr double kDiameter = 0.012;  ///< m, D_f of the scenario's pile
constexpr double kSurface = 0.030;   ///< m, the region's top, where the pile starts

std::filesystem::path run_scenario(const std::string& name, std::chrono::seconds limit) {
  auto folder = fresh_directory(name);
  const CommandResult result =
      run_command({coupler(), "run", (e2e_dir() / "scenarios" / (name + ".json")).string(), "--out", folder.string(), "--no-progress"}, limit);
  EXPECT_EQ(result.exit_status, 0) << result.output;
  return folder;
}

const std::filesystem::path& small_study() {
  static const std::filesystem::path dir = run_scenario("centrifuge_pile_small", std::chrono::seconds(900));
  return dir;
}

std::filesystem::path results_of(const std::string& label) { return small_study() / label / "results.h5"; }

std::vector<std::string> snapshot_names(const h5::File& file) {
  auto names = h5::list_members(file, "/snapshots/dem");
  std::sort(names.begin(), names.end());
  return names;
}

TEST(CentrifugeFoundation, ThePileStartsOnlyAfterTheGenerationEquilibrium) {
  // pile.start_when: rest until the DEM's unbalanced-force ratio is at most
  // 0.002, at or after step 200; the record before the first move says so.
  const auto path = results_of("g100_p1");
  const auto moved = series(path, "dem_pile_displacement_m");
  const auto ratio = series(path, "dem_unbalanced_force_ratio");
  const auto step = series(path, "step_dem");
  const auto first = std::size_t(std::find_if(moved.begin(), moved.end(), [](double d) { return d > 0.0; }) - moved.begin());
  ASSERT_GT(first, 1u);
  ASSERT_LT(first, moved.size());
  EXPECT_LE(ratio[first - 1], 0.002);
  EXPECT_GE(step[first - 1], 200.0);
  for (std::size_t k = 0; k + 1 < first; ++k) EXPECT_GT(ratio[k], 0.002) << "record " << k << ": in equilibrium, yet the pile waited";
  std::cout << "pile starts after DEM step " << step[first - 1] << " (ratio " << ratio[first - 1] << ")\n";
}

TEST(CentrifugeFoundation, TipAndShaftMakeUpThePileForce) {
  const auto path = results_of("g100_p1");
  const auto total = series(path, "dem_pile_force_n");
  const auto tip = series(path, "dem_pile_tip_force_n");
  const auto shaft = series(path, "dem_pile_shaft_force_n");
  // shaft is computed as total - tip: exact up to one rounding of the sum.
  for (std::size_t k = 0; k < total.size(); ++k) EXPECT_NEAR(tip[k] + shaft[k], total[k], 1e-12 * (1.0 + std::abs(total[k])));
  // A flat foundation at the surface carries its load on its end (the facets
  // of the flat end own its rim edge): at the peak the tip takes most of it.
  const auto peak = std::size_t(std::max_element(total.begin(), total.end()) - total.begin());
  EXPECT_GT(tip[peak], 0.8 * total[peak]);
}

TEST(CentrifugeFoundation, BondsBreakFirstBeneathTheTip) {
  // At the first snapshot after the peak (the collapse), the fraction of
  // bonds broken within 1 D_f below the tip (r <= D_f/2) against the far
  // field (the outer ring D_f/2 wide, deeper than 1 D_f below the tip).
  // factor 3 is far below the measured one (docs/centrifuge_foundation.md)
  // and far above 1, where breakage would not be localised.
  const auto path = results_of("g100_p1");
  const auto time = series(path, "time_s");
  const auto force = series(path, "dem_pile_force_n");
  const auto moved = series(path, "dem_pile_displacement_m");
  const auto peak = std::size_t(std::max_element(force.begin(), force.end()) - force.begin());
  const h5::File file = h5::File::open_read_only(path);
  std::string after;
  for (const std::string& name : snapshot_names(file))
    if (h5::read_double_attribute(file.root().open_group("snapshots/dem/" + name).id(), "time") >= time[peak]) {
      after = name;
      break;
    }
  ASSERT_FALSE(after.empty());
  const std::string snap = "/snapshots/dem/" + after;
  const double tip = kSurface - moved[peak];
  const auto where = h5::read_f64(file, snap + "/bond_position");
  const auto state = h5::read_i64(file, snap + "/bond_state");
  double r_max = 0.0;
  for (std::size_t b = 0; b < state.size(); ++b) r_max = std::max(r_max, std::hypot(where[3 * b], where[3 * b + 1]));
  int below_n = 0, below_broken = 0, far_n = 0, far_broken = 0;
  for (std::size_t b = 0; b < state.size(); ++b) {
    const double r = std::hypot(where[3 * b], where[3 * b + 1]), z = where[3 * b + 2];
    const bool broken = state[b] == 3 || state[b] == 4;  // bond_state.hpp: broken in tension, in shear
    if (r <= 0.5 * kDiameter && z < tip && z >= tip - kDiameter) {
      ++below_n;
      below_broken += broken;
    } else if (r >= r_max - 0.5 * kDiameter && z < tip - kDiameter) {
      ++far_n;
      far_broken += broken;
    }
  }
  ASSERT_GT(below_n, 50);
  ASSERT_GT(far_n, 50);
  const double below = double(below_broken) / below_n, outside = double(far_broken) / far_n;
  std::cout << "broken fraction beneath the tip " << below << " (" << below_n << " bonds), far field " << outside << " (" << far_n << ")\n";
  EXPECT_GT(below, 2.0 * outside);
}

TEST(CentrifugeFoundation, TheParticlesForcesBalanceWithinOnePercentWithoutTheDamping) {
  // The check: foundation force + particle weight = the reactions of
  // the boundary walls and the FDM + the rate of change of the particles'
  // momentum, within 1 % averaged over the loading (h > 0.5 mm, after the
  // ramp). What no boundary carries is the local damping force; the loading
  // runs at the study's 0.03125 m/s with alpha 0.2 (pile.local_damping) to
  // keep it small. Measured on this variant: 0.67 % to 6 mm; at twice the
  // rate 0.63 %, then 1.08 % after a change of bits alone (whole runs at that
  // rate: 1.1-1.7 % at 100 g; docs/centrifuge_foundation.md, Force balance);
  // at 0.25 m/s with alpha 0.7 it was 11 %, so the check can fail.
  const auto results = results_of("g100_p1");
  const auto time = series(results, "time_s");
  const auto moved = series(results, "dem_pile_displacement_m");
  const auto pile = series(results, "dem_wall_pile_force_n");    // [n, 3], force of the particles on the wall
  const auto floor = series(results, "dem_wall_floor_force_n");  // [n, 3]
  const auto coupling = series(results, "dem_interface_force_reaction");  // [n, 3], on the particles
  const auto weight = series(results, "dem_total_weight_n");
  const auto momentum = series(results, "dem_particle_momentum_n_s");  // [n, 3]
  const auto damping = series(results, "dem_damping_force_n");         // [n, 3]
  double residual = 0.0, closure = 0.0, scale = 0.0;
  int n = 0;
  for (std::size_t k = 1; k < time.size(); ++k) {
    if (moved[k] <= 0.5e-3) continue;
    // Averages of record k are over (t_{k-1}, t_k]: the momentum change over the same interval.
    const double rate = (momentum[3 * k + 2] - momentum[3 * (k - 1) + 2]) / (time[k] - time[k - 1]);
    const double boundaries = -pile[3 * k + 2] - floor[3 * k + 2] + coupling[3 * k + 2] - weight[k];
    residual += rate - boundaries;
    closure += rate - boundaries - damping[3 * k + 2];
    scale += std::abs(pile[3 * k + 2]) + weight[k];
    ++n;
  }
  ASSERT_GT(n, 100);
  std::cout << "momentum balance over " << n << " records: residual without damping " << residual / scale << ", with it " << closure / scale
            << " of the foundation force plus the weight\n";
  EXPECT_LT(std::abs(residual) / scale, 0.01);
  EXPECT_LT(std::abs(closure) / scale, 1e-6);  // with the damping term it closes (MomentumBalance.*): the bookkeeping is right
}

TEST(CentrifugeFoundation, ARunRepeatsBitForBit) {
  // Same packing, same thread count (1): the same numbers to the last bit.
  for (const char* column : {"dem_pile_force_n", "dem_pile_tip_force_n", "dem_bonds_broken_shear", "dem_pile_displacement_m"})
    EXPECT_EQ(series(results_of("g100_p1"), column), series(results_of("g100_p1_repeat"), column)) << column;
  const h5::File a = h5::File::open_read_only(results_of("g100_p1"));
  const h5::File b = h5::File::open_read_only(results_of("g100_p1_repeat"));
  const std::string last = "/snapshots/dem/" + snapshot_names(a).back();
  EXPECT_EQ(h5::read_f64(a, last + "/particle_position"), h5::read_f64(b, last + "/particle_position"));
  EXPECT_EQ(h5::read_i64(a, last + "/bond_state"), h5::read_i64(b, last + "/bond_state"));
}

TEST(CentrifugeFoundation, TheInertialNumberMonitorIsThePushRateOverTheGrainPressureTime) {
  // pile_inertial_number (inertial_number.hpp): I = (v/D_f) d / sqrt(p_tip / rho_s).
  // 0 while the pile rests; at full speed (after the ramp) it must equal the
  // closed form from the run's own tip force, the speed and size of the small
  // variant's pile, the body's mean sphere diameter (last snapshot: the radii do
  // not change once generated) and grain density (scenario: 2650 kg/m3).
  constexpr double kSpeed = 0.03125;      // m/s, the study's pile.velocity_m_s (the small variant keeps it)
  constexpr double kRampSteps = 32000.0;  // its pile.ramp_steps
  constexpr double kGrainDensity = 2650.0;
  const auto path = results_of("g100_p1");
  const auto inertial = series(path, "dem_pile_inertial_number");
  const auto moved = series(path, "dem_pile_displacement_m");
  const auto tip = series(path, "dem_pile_tip_force_n");
  const auto step = series(path, "step_dem");
  const h5::File file = h5::File::open_read_only(path);
  const auto radius = h5::read_f64(file, "/snapshots/dem/" + snapshot_names(file).back() + "/particle_radius");
  double diameter = 0.0;
  for (double r : radius) diameter += 2.0 * r;
  diameter /= double(radius.size());
  const auto first = std::size_t(std::find_if(moved.begin(), moved.end(), [](double d) { return d > 0.0; }) - moved.begin());
  ASSERT_GT(first, 1u);
  for (std::size_t k = 0; k + 1 < first; ++k) EXPECT_EQ(inertial[k], 0.0) << "record " << k << ": the pile rests";
  const double area = std::acos(-1.0) * kDiameter * kDiameter / 4.0;
  int checked = 0;
  std::vector<double> full_speed;
  for (std::size_t k = first; k < inertial.size(); ++k) {
    if (step[k] < step[first - 1] + kRampSteps) continue;
    full_speed.push_back(inertial[k]);
    if (!(tip[k] > 0.0)) {
      EXPECT_EQ(inertial[k], 1.0) << "record " << k << ": an unloaded tip reports the cap";
      continue;
    }
    const double expected = std::min(1.0, kSpeed / kDiameter * diameter / std::sqrt(tip[k] / area / kGrainDensity));
    // The mean diameter is summed in another order here than in the server: round-off only.
    EXPECT_NEAR(inertial[k], expected, 1e-9 * expected) << "record " << k;
    ++checked;
  }
  EXPECT_GT(checked, 100);
  std::sort(full_speed.begin(), full_speed.end());
  const double median = full_speed[full_speed.size() / 2];
  std::cout << "inertial number at full speed: median " << median << " over " << full_speed.size() << " records\n";
  EXPECT_LT(median, 1e-2);  // the study's rate: docs/resolution.md finds about 1e-3 (quasi-static)
}

/// Mean pile force over penetrations 0.25 D_f to 1 D_f: the resistance after
/// the collapse below the tip (a single record's force jumps by tens of per
/// cent as bonds break; tools/centrifuge_foundation.py reads it the same way).
double mean_resistance(const std::filesystem::path& results) {
  const auto force = series(results, "dem_pile_force_n");
  const auto moved = series(results, "dem_pile_displacement_m");
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < force.size(); ++k)
    if (moved[k] >= 0.25 * kDiameter && moved[k] <= kDiameter) {
      sum += force[k];
      ++n;
    }
  EXPECT_GT(n, 100);
  return sum / n;
}

TEST(CentrifugeFoundationSlow, ResistanceGrowsWithTheGLevelBeyondTheScatter) {
  // The same REV (rev.stress_pa fixed) at 1 g and 100 g on three packings:
  // only the self-weight stress scaled into the bonds and gravity differ.
  // Over the same penetrations every 100 g packing must resist more than
  // every 1 g packing (measured 40.6-42.4 N against 15.2-19.0 N at 0.03125
  // m/s with alpha 0.2 during the loading; the study, docs/centrifuge_foundation.md §4). The initial peak
  // does not separate: the packing decides it (docs/centrifuge_foundation.md §4).
  // Six runs of about 8.5 min each at one DEM thread.
  const std::filesystem::path dir = run_scenario("centrifuge_pile_glevels", std::chrono::seconds(6900));
  double lowest_100g = std::numeric_limits<double>::infinity(), highest_1g = 0.0;
  for (const char* packing : {"p1", "p2", "p3"}) {
    const double at_1g = mean_resistance(dir / (std::string("g1_") + packing) / "results.h5");
    const double at_100g = mean_resistance(dir / (std::string("g100_") + packing) / "results.h5");
    std::cout << "packing " << packing << ": mean force over 0.25-1 D_f " << at_1g << " N at 1 g, " << at_100g << " N at 100 g\n";
    highest_1g = std::max(highest_1g, at_1g);
    lowest_100g = std::min(lowest_100g, at_100g);
  }
  EXPECT_GT(lowest_100g, highest_1g);
}

}  // namespace
}  // namespace dfc::testing
