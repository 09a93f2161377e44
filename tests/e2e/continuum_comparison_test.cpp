// The same coupled pile run against three continua, changing only
// participants.continuum.program (docs/continuum_comparison.md):
// fdm_server (explicit, elastic), elastic_reference_server (implicit, static,
// the same elastic zones) and rigid_continuum_server (fixed walls).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

struct PileRun {
  std::vector<double> force;
  std::vector<double> on_continuum_z, on_dem_z;
  std::vector<double> continuum_power, continuum_unbalanced;
  std::string versions;
};

PileRun run_pile_short_with(const std::string& program) {
  const auto dir = fresh_directory("pile_short_continuum_" + program);
  auto scenario = nlohmann::json::parse(read_text(e2e_dir() / "scenarios/pile_short.json"));
  scenario["participants"]["continuum"]["program"] = program;
  const auto file = dir / "scenario.json";
  std::ofstream(file) << scenario.dump(2);
  const CommandResult result = run_command({coupler(), "run", file.string(), "--out", (dir / "out").string(), "--no-progress"}, std::chrono::seconds(300));
  EXPECT_EQ(result.exit_status, 0) << result.output;
  const auto h5file = h5::File::open_read_only(dir / "out/results.h5");
  const auto column = [&](const std::string& name) { return h5::read_f64(h5file, "/timeseries/" + name); };
  return {column("dem_pile_force_n"),         column("interface_force_on_continuum_z"),   column("interface_force_on_dem_z"),
          column("continuum_interface_power_w"), column("continuum_unbalanced_force_ratio"), h5::read_string_attribute(h5file, "/", "versions")};
}

/// Mean pile force over the first and the last third of the samples after first contact.
std::pair<double, double> early_and_late_force(const std::vector<double>& force) {
  const auto first = std::find_if(force.begin(), force.end(), [](double f) { return f > 0.0; });
  const auto third = (force.end() - first) / 3;
  return {std::accumulate(first, first + third, 0.0) / double(third), std::accumulate(force.end() - third, force.end(), 0.0) / double(third)};
}

TEST(ContinuumComparison, ElasticReferenceAndFdmGiveTheSamePileResistanceWithinTheGranularScatter) {
  const PileRun fdm = run_pile_short_with("fdm_server");
  const PileRun reference = run_pile_short_with("elastic_reference_server");
  const PileRun rigid = run_pile_short_with("rigid_continuum_server");

  for (const PileRun* run : {&fdm, &reference, &rigid}) {
    // Force balance read back from the file, independently of the coupler's own check.
    ASSERT_EQ(run->on_continuum_z.size(), run->on_dem_z.size());
    for (std::size_t i = 0; i < run->on_dem_z.size(); ++i)
      ASSERT_NEAR(run->on_dem_z[i] + run->on_continuum_z[i], 0.0, 1e-9 * std::max(1.0, std::abs(run->on_dem_z[i]))) << "exchange " << i + 1;
    // Every continuum lets the pile build up resistance as it penetrates.
    const auto [early, late] = early_and_late_force(run->force);
    EXPECT_GT(late, 2.0 * early) << run->versions;
  }
  EXPECT_NE(reference.versions.find("elastic_reference_server"), std::string::npos);
  // The static reference is always in equilibrium, and its wall moves (it absorbs work).
  for (const double ratio : reference.continuum_unbalanced) EXPECT_EQ(ratio, 0.0);
  EXPECT_TRUE(std::any_of(reference.continuum_power.begin(), reference.continuum_power.end(), [](double p) { return p != 0.0; }));

  const double fdm_late = early_and_late_force(fdm.force).second;
  const double reference_late = early_and_late_force(reference.force).second;
  const double rigid_late = early_and_late_force(rigid.force).second;
  const double difference = std::abs(fdm_late - reference_late) / (0.5 * (fdm_late + reference_late));
  std::cout << "pile_short, mean pile force over the last third of the push: fdm_server " << fdm_late << " N, elastic_reference_server "
            << reference_late << " N, rigid_continuum_server " << rigid_late << " N; fdm vs reference " << difference << "\n";
  // Both elastic continua are the same discretized body (the reference is the
  // explicit solver's static limit to 2e-7, reference_tests), so any
  // systematic difference comes from the explicit solver's dynamics (mass
  // scaling, damping) lagging the static answer. Here E = 50 MPa is ~10× the
  // bed's own stiffness (k_n/2R ≈ 4 MPa): the wall moves some 0.05 mm against
  // 2.5 mm grains, and what separates the curves is the bed's sensitivity to
  // such µm differences (the packing evolves chaotically). Measured on this
  // scenario: 8.71 N (fdm) vs 9.96 N (reference), 13 % (24 % before the
  // contact twirl and the wall history carried across facets, which moved the
  // packing's path); the rigid walls, 9.14 N, fall between the two elastic
  // runs, which shows the spread is granular scatter, not stiffness. The bound
  // 35 % is that scatter with margin;
  // a reference that returned wrong displacements (wrong sign, missing in-situ
  // state, unit errors) moves the wall by millimetres and changes the force by
  // far more (a soft E = 2 MPa continuum already breaks the DEM's contacts).
  EXPECT_LT(difference, 0.35);
  // No "rigid >= elastic" assertion: at this stiffness ratio the ordering is
  // inside the granular scatter (docs/continuum_comparison.md).
}

}  // namespace
}  // namespace dfc::testing
