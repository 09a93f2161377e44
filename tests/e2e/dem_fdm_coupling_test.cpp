// DEM–FDM coupling through the real processes (issue checks 3 and 7, docs/theory/coupling.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

double mean_of_tail(const std::vector<double>& values, double fraction) {
  const auto first = values.end() - static_cast<std::ptrdiff_t>(double(values.size()) * fraction);
  return std::accumulate(first, values.end(), 0.0) / double(values.end() - first);
}

std::filesystem::path run_scenario(const std::string& scenario, const std::string& out_name, const std::vector<std::string>& extra = {}) {
  const auto dir = fresh_directory(out_name);
  std::vector<std::string> argv{coupler(), "run", (e2e_dir() / "scenarios" / scenario).string(), "--out", dir.string(), "--no-progress"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  const CommandResult result = run_command(argv, std::chrono::seconds(300));
  EXPECT_EQ(result.exit_status, 0) << result.output;
  return dir / "results.h5";
}

// Check 3: a DEM bed resting under gravity on an FDM block. Side walls are
// frictionless, so the floor — the coupling wall — carries the whole weight.
// A granular bed relaxed by local damping never comes fully to rest (particles
// keep rattling and spinning, as the linear law has no rolling resistance):
// the instantaneous floor force scatters by about ±0.5 % around the weight.
// Its time average over the last quarter of the run is the static load up to
// the change of the bed's vertical momentum over that window divided by the
// window length, which the small kinetic energy at the end bounds far below
// 0.5 %. So: the average force the FDM received equals the weight within 0.5 %.
TEST(DemFdmCoupling, BedOnBlockTransmitsItsWeight) {
  const auto results = run_scenario("bed_on_block.json", "bed_on_block");
  const auto weight = series(results, "dem_total_weight_n");
  const auto on_continuum = series(results, "interface_force_on_continuum_z");
  const auto on_dem = series(results, "interface_force_on_dem_z");
  ASSERT_GT(weight.back(), 0.0);
  const double average = mean_of_tail(on_continuum, 0.25);
  const double relative = std::abs(-average - weight.back()) / weight.back();
  std::cout << "bed on block: weight " << weight.back() << " N, mean force on the FDM " << average << " N, relative error " << relative << "\n";
  EXPECT_LT(relative, 0.005);
  // Equal and opposite at every exchange (the coupler also enforces it; here
  // it is read back from the file, independently of that check).
  ASSERT_EQ(on_continuum.size(), on_dem.size());
  for (std::size_t i = 0; i < on_dem.size(); ++i)
    ASSERT_NEAR(on_dem[i] + on_continuum[i], 0.0, 1e-9 * std::max(1.0, std::abs(on_dem[i]))) << "exchange " << i + 1;
}

// Check 7: in the demo's short variant the pile force grows with penetration:
// a clear upward trend over the push, not noise around zero.
TEST(DemFdmCoupling, PileForceGrowsWithPenetration) {
  const auto results = run_scenario("pile_short.json", "pile_short");
  const auto displacement = series(results, "dem_pile_displacement_m");
  const auto force = series(results, "dem_pile_force_n");
  // Samples once the pile has reached the bed (first positive force).
  std::size_t first = 0;
  while (first < force.size() && !(force[first] > 0.0)) ++first;
  ASSERT_LT(first + 20, force.size()) << "the pile never reached the bed";
  const std::size_t n = force.size() - first;
  // Least-squares slope of force against penetration, and the mean force in
  // the last third against the first third of the push.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = first; i < force.size(); ++i) {
    sx += displacement[i], sy += force[i], sxx += displacement[i] * displacement[i], sxy += displacement[i] * force[i];
  }
  const double slope = (double(n) * sxy - sx * sy) / (double(n) * sxx - sx * sx);
  const std::vector<double> pushed(force.begin() + static_cast<std::ptrdiff_t>(first), force.end());
  const double early = std::accumulate(pushed.begin(), pushed.begin() + static_cast<std::ptrdiff_t>(n / 3), 0.0) / double(n / 3);
  const double late = std::accumulate(pushed.end() - static_cast<std::ptrdiff_t>(n / 3), pushed.end(), 0.0) / double(n / 3);
  std::cout << "pile: slope " << slope << " N/m, mean force first third " << early << " N, last third " << late << " N\n";
  EXPECT_GT(slope, 0.0);
  EXPECT_GT(late, 2.0 * early);
  EXPECT_GT(late, 0.0);
}

// The continuum is swapped by changing only `program`: the same pile run
// against the rigid reference continuum completes with balanced interface
// forces, and a rigid far field resists at least as much as the elastic one
// would — here only that it resists (positive force at the end).
TEST(DemFdmCoupling, RigidReferenceContinuumSwapsIn) {
  const auto dir = fresh_directory("pile_short_rigid");
  auto scenario = nlohmann::json::parse(read_text(e2e_dir() / "scenarios/pile_short.json"));
  scenario["participants"]["continuum"]["program"] = "rigid_continuum_server";
  scenario["name"] = "pile_short_rigid";
  const auto file = dir / "scenario.json";
  std::ofstream(file) << scenario.dump(2);
  const CommandResult result = run_command({coupler(), "run", file.string(), "--out", (dir / "out").string(), "--no-progress"}, std::chrono::seconds(300));
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const auto h5file = h5::File::open_read_only(dir / "out/results.h5");
  const auto velocity_power = h5::read_f64(h5file, "/timeseries/continuum_interface_power_w");
  for (const double p : velocity_power) EXPECT_EQ(p, 0.0) << "a rigid continuum absorbs no work";
  const auto force = h5::read_f64(h5file, "/timeseries/dem_pile_force_n");
  EXPECT_GT(force.back(), 0.0);
  EXPECT_NE(h5::read_string_attribute(h5file, "/", "versions").find("rigid_continuum_server"), std::string::npos);
}

}  // namespace
}  // namespace dfc::testing

namespace dfc::testing {
namespace {

// Determinism (developers' standards): the same scenario and thread count give
// the same output bit for bit — every recorded series of a coupled DEM–FDM
// run, except the wall-clock column, is identical between two runs.
TEST(DemFdmCoupling, CoupledRunIsBitForBitRepeatable) {
  const auto first = run_scenario("pile_short.json", "pile_short_repeat_a");
  const auto second = run_scenario("pile_short.json", "pile_short_repeat_b");
  const auto a = h5::File::open_read_only(first);
  const auto b = h5::File::open_read_only(second);
  const auto columns = h5::list_members(a, "/timeseries");
  ASSERT_GT(columns.size(), 10u);
  for (const auto& column : columns) {
    if (column == "wall_time_s") continue;
    const auto x = h5::read_f64(a, "/timeseries/" + column);
    const auto y = h5::read_f64(b, "/timeseries/" + column);
    ASSERT_EQ(x.size(), y.size()) << column;
    for (std::size_t i = 0; i < x.size(); ++i)
      ASSERT_TRUE(std::memcmp(&x[i], &y[i], sizeof(double)) == 0) << column << " differs at row " << i << ": " << x[i] << " vs " << y[i];
  }
}

}  // namespace
}  // namespace dfc::testing
