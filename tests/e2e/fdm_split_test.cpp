// Coupling verification (docs/theory/coupling.md §5, issue check 2): an elastic box split at a
// plane into two fdm_servers coupled through the coupler — the lower half
// provides the interface, the upper half is driven by its velocities and
// returns its interface forces and masses, exactly the path a DEM takes — must
// reach the same static solution as the unsplit box under the same load.
//
// Tolerance: both runs converge by damped relaxation to the same discrete
// equilibrium (the split adds the same nodal force terms, in another order),
// so the difference is set by how far each run has converged, not by the
// coupling. We run both to an unbalanced-force ratio far below 1e-9 and
// require a relative displacement error below 1e-6, the target.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

struct GridField {
  std::vector<double> position;
  std::vector<double> displacement;
};

GridField last_grid_snapshot(const std::filesystem::path& results, const std::string& role) {
  const auto file = h5::File::open_read_only(results);
  const auto snapshots = h5::list_members(file, "/snapshots/" + role);
  const std::string last = "/snapshots/" + role + "/" + snapshots.back();
  return {h5::read_f64(file, last + "/node_position"), h5::read_f64(file, last + "/node_displacement")};
}

// Gridpoint displacement keyed by rounded position (positions are exact
// multiples of the zone size, so rounding to 1e-9 m identifies them).
using Key = std::array<long long, 3>;
void add_field(std::map<Key, std::array<double, 3>>& out, const GridField& grid) {
  for (std::size_t i = 0; i < grid.position.size() / 3; ++i) {
    Key key;
    for (std::size_t c = 0; c < 3; ++c) key[c] = std::llround(grid.position[3 * i + c] * 1e9);
    out[key] = {grid.displacement[3 * i], grid.displacement[3 * i + 1], grid.displacement[3 * i + 2]};
  }
}

TEST(FdmSplit, SplitBoxMatchesUnsplitBox) {
  const auto dir = fresh_directory("fdm_split");
  const auto unsplit = run_command({coupler(), "run", (e2e_dir() / "scenarios/box_unsplit.json").string(), "--out", (dir / "unsplit").string(),
                                    "--no-progress"},
                                   std::chrono::seconds(300));
  ASSERT_EQ(unsplit.exit_status, 0) << unsplit.output;
  const auto split = run_command({coupler(), "run", (e2e_dir() / "scenarios/box_split.json").string(), "--out", (dir / "split").string(),
                                  "--no-progress"},
                                 std::chrono::seconds(300));
  ASSERT_EQ(split.exit_status, 0) << split.output;

  std::map<Key, std::array<double, 3>> reference;
  add_field(reference, last_grid_snapshot(dir / "unsplit/results.h5", "continuum"));
  std::map<Key, std::array<double, 3>> coupled;
  add_field(coupled, last_grid_snapshot(dir / "split/results.h5", "continuum"));
  add_field(coupled, last_grid_snapshot(dir / "split/results.h5", "dem"));
  ASSERT_EQ(coupled.size(), reference.size()) << "interface gridpoints must coincide";

  double max_reference = 0.0;
  double max_difference = 0.0;
  for (const auto& [key, u] : reference) {
    const auto it = coupled.find(key);
    ASSERT_NE(it, coupled.end());
    for (std::size_t c = 0; c < 3; ++c) {
      max_reference = std::max(max_reference, std::abs(u[c]));
      max_difference = std::max(max_difference, std::abs(u[c] - it->second[c]));
    }
  }
  ASSERT_GT(max_reference, 1e-5) << "the load must produce a measurable displacement";
  const double relative = max_difference / max_reference;
  RecordProperty("relative_displacement_error", std::to_string(relative));
  std::cout << "split vs unsplit: max |u| = " << max_reference << " m, max |Δu| = " << max_difference << " m, relative " << relative << "\n";
  EXPECT_LT(relative, 1e-6);

  // The coupler recorded the interface forces of both sides: equal and opposite.
  const auto file = h5::File::open_read_only(dir / "split/results.h5");
  const auto on_dem = h5::read_f64(file, "/timeseries/interface_force_on_dem_z");
  const auto on_continuum = h5::read_f64(file, "/timeseries/interface_force_on_continuum_z");
  ASSERT_EQ(on_dem.size(), on_continuum.size());
  for (std::size_t i = 0; i < on_dem.size(); ++i) EXPECT_NEAR(on_dem[i] + on_continuum[i], 0.0, 1e-9 * std::abs(on_dem[i]) + 1e-12);
}

}  // namespace
}  // namespace dfc::testing
