// The continuum pile (docs/continuum_pile.md §6; issue 41) through the real
// coupler and continuum_server, a single participant: the small variant
// tests/e2e/scenarios/open_pile_continuum_small.json (the 8 mm tube jacked
// 2 mm into chalk_snw structured Cam clay on a coarse mesh, about 10 s), run
// once for all the checks, and the same with remeshing
// (open_pile_continuum_small_remesh.json).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "e2e_paths.hpp"
#include "results_series.hpp"

namespace dfc::testing {
namespace {

/// Runs tests/e2e/scenarios/<name>.json into a fresh folder; its results file.
std::filesystem::path run_scenario(const std::string& name) {
  const auto folder = fresh_directory(name);
  const CommandResult run =
      run_command({coupler(), "run", (e2e_dir() / "scenarios" / (name + ".json")).string(), "--out", folder.string(), "--no-progress"},
                  std::chrono::seconds(300));
  EXPECT_EQ(run.exit_status, 0) << run.output;
  return folder / "results.h5";
}

const std::filesystem::path& results() {
  static const std::filesystem::path file = run_scenario("open_pile_continuum_small");
  return file;
}

std::vector<double> column(const std::string& monitor) { return series(results(), "continuum_" + monitor); }

nlohmann::json config() {
  std::ifstream in(results().parent_path() / "scenario.json");
  return nlohmann::json::parse(in).at("participants").at("continuum").at("config");
}

TEST(OpenPileContinuum, ReachesTheDepthAndTheForceGrowsWithPenetration) {
  const std::vector<double> depth = column("pile_displacement_m");
  const std::vector<double> force = column("pile_force_n");
  ASSERT_EQ(depth.size(), force.size());
  ASSERT_GE(depth.size(), 10u);
  EXPECT_NEAR(depth.back(), config().at("pile").at("depth_m").get<double>(), 1e-9);
  // At 2 mm (two wall thicknesses) the tip is still being mobilised (the
  // force rises by 3.5 % over the last exchange): it rises at every exchange.
  for (std::size_t i = 1; i < force.size(); ++i) EXPECT_GT(force[i], force[i - 1]) << "exchange " << i;
  EXPECT_GT(force.front(), 0.0);
}

TEST(OpenPileContinuum, FaceForcesSumToThePileForce) {
  const std::vector<double> total = column("pile_force_n");
  const std::vector<double> annulus = column("pile_annulus_force_n");
  const std::vector<double> inner = column("pile_inner_shaft_force_n");
  const std::vector<double> outer = column("pile_outer_shaft_force_n");
  for (std::size_t i = 0; i < total.size(); ++i)
    EXPECT_NEAR(annulus[i] + inner[i] + outer[i], total[i], 1e-9 * std::abs(total[i])) << "exchange " << i;
  // The annulus carries the resistance (at 2 mm the shafts have barely any
  // soil against them on this mesh, docs/continuum_pile.md §6.4).
  EXPECT_GT(annulus.back(), 0.5 * total.back());
}

// Global equilibrium: the base carries the pile's force and the surcharge
// σ_v on the surface outside the annulus, σ_v π (R² − (r_o² − r_i²)). Once
// the motion is quasi-static (unbalanced-force ratio below 5e-3) the
// imbalance is of the order of that ratio: 1 %.
TEST(OpenPileContinuum, TheBaseCarriesThePileForceAndTheSurcharge) {
  const nlohmann::json c = config();
  const double radius = c.at("mesh").at("radius_m").get<double>();
  const double ri = c.at("pile").at("inner_radius_m").get<double>();
  const double ro = c.at("pile").at("outer_radius_m").get<double>();
  const double surcharge = c.at("initial_stress").at("vertical_pa").get<double>() * std::numbers::pi * (radius * radius - (ro * ro - ri * ri));
  const std::vector<double> force = column("pile_force_n");
  const std::vector<double> base = column("base_reaction_n");
  const std::vector<double> unbalanced = column("unbalanced_force_ratio");
  int checked = 0;
  for (std::size_t i = 0; i < force.size(); ++i) {
    if (unbalanced[i] > 5e-3) continue;
    ++checked;
    EXPECT_NEAR(base[i], force[i] + surcharge, 0.01 * (force[i] + surcharge)) << "exchange " << i;
  }
  EXPECT_GE(checked, int(force.size()) / 2);
  EXPECT_LT(unbalanced.back(), 5e-3);
}

// The soil enters the tube: a plug forms (length L > 0) and stays shorter
// than the penetration h (no heave inside the tube), and it forms: the
// incremental filling ratio IFR = dL/dh (docs/open_pile.md §2) of the second
// half of the push is below the plug length ratio L/h of the first (measured
// 0.43 against 0.74).
TEST(OpenPileContinuum, SoilEntersTheTube) {
  const std::vector<double> depth = column("pile_displacement_m");
  const std::vector<double> plug = column("pile_plug_length_m");
  std::cout << "plug length " << plug.back() * 1e3 << " mm at " << depth.back() * 1e3 << " mm, force " << column("pile_force_n").back()
            << " N\n";
  EXPECT_GT(plug.back(), 0.0);
  EXPECT_LT(plug.back(), depth.back());
  const std::size_t n = depth.size();
  const double first = plug[n / 2] / depth[n / 2];
  const double second = (plug[n - 1] - plug[n / 2]) / (depth[n - 1] - depth[n / 2]);
  EXPECT_LT(second, first);
}

// Remeshing during the push (docs/continuum_pile.md §5, §6.5): the run
// remeshes (at 1.8 mm), reaches the depth and re-equilibrates: at the end the
// base carries the pile and the surcharge to 1 %. The remesh keeps each
// node's out-of-balance force, so the force rises through it as at every
// exchange, and after it follows the run that was not remeshed to the
// issue's 1 % (measured +0.18 % and +0.34 % at 1.9 and 2 mm; before the
// equilibrium correction it fell from 1 007 to 804 N).
TEST(OpenPileContinuum, RemeshedRunReachesTheDepthAndReEquilibrates) {
  const std::filesystem::path file = run_scenario("open_pile_continuum_small_remesh");
  const std::vector<double> remeshes = series(file, "continuum_remeshes");
  const std::vector<double> force = series(file, "continuum_pile_force_n");
  const std::vector<double> base = series(file, "continuum_base_reaction_n");
  const std::vector<double> depth = series(file, "continuum_pile_displacement_m");
  const std::vector<double> not_remeshed = column("pile_force_n");
  ASSERT_FALSE(remeshes.empty());
  ASSERT_EQ(force.size(), not_remeshed.size());
  EXPECT_GE(remeshes.back(), 1.0);
  EXPECT_NEAR(depth.back(), 0.002, 1e-9);
  std::size_t first = 0;
  while (first < remeshes.size() && remeshes[first] < 1.0) ++first;
  ASSERT_GT(first, 0u);
  for (std::size_t i = 1; i < force.size(); ++i) EXPECT_GT(force[i], force[i - 1]) << "exchange " << i;
  for (std::size_t i = first; i < force.size(); ++i)
    EXPECT_NEAR(force[i], not_remeshed[i], 0.01 * not_remeshed[i]) << "exchange " << i << " (remeshed at exchange " << first << ")";
  const nlohmann::json c = config();
  const double radius = c.at("mesh").at("radius_m").get<double>();
  const double ri = c.at("pile").at("inner_radius_m").get<double>();
  const double ro = c.at("pile").at("outer_radius_m").get<double>();
  const double surcharge = c.at("initial_stress").at("vertical_pa").get<double>() * std::numbers::pi * (radius * radius - (ro * ro - ri * ri));
  EXPECT_NEAR(base.back(), force.back() + surcharge, 0.01 * (force.back() + surcharge));
}

}  // namespace
}  // namespace dfc::testing
