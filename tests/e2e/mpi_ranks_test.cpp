// The DEM on many MPI processes gives the bits of one (issue "Beyond one
// machine"; docs/determinism.md §3): each scenario runs through the real
// coupler with participants.dem.mpi_ranks 1 (one process, no MPI) and N, and
// the two results files must agree to the bit:
//  - every time-series column (the DEM's monitors and forces, the pile's
//    force split and plug, the continuum's side, the interface balance),
//    except the wall-clock time;
//  - every DEM snapshot's arrays, all written (the snapshot block's contents
//    particle_stress, bonds, contacts and walls): the particles (position,
//    velocity, radius, stress, matched by particle id: a body on many
//    processes is written in id order), the bonds and contacts (matched by
//    the ids of their two particles; their index columns must name the same
//    particles), a generated body's stress profile, and the walls.
// The scenarios: the bonded coupled pile (tests/e2e/scenarios/pile_bonded_restart.json:
// soft bonds that break, the pile with its own damping, lists rebuilt), the
// open pile's small variant (graded PCRM body, the coupling wall, the plug),
// the graded generation's small variant (generation on every process, then
// decomposed, run to equilibrium), and the triaxial-walls and UCS small
// variants (60 exchanges each: a prepared sample, servo-controlled walls).
// Ranks 3 and 4 run the bonded pile (label long), the open pile and the
// graded generation (label slow). Built only where CMake found MPI.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

/// `scenario` as the coupler reads it (its first variant, includes resolved),
/// with the DEM on `ranks` processes (and at most `exchanges` exchanges, 0:
/// the scenario's), written into `folder`.
std::filesystem::path on_ranks(const std::filesystem::path& scenario, int ranks, const std::filesystem::path& folder, int exchanges) {
  const CommandResult expanded = run_command({coupler(), "expand", scenario.string()}, std::chrono::seconds(60));
  EXPECT_EQ(expanded.exit_status, 0) << expanded.output;
  nlohmann::json run = nlohmann::json::parse(expanded.output);
  if (run.is_array()) run = run.at(0);
  run["participants"]["dem"]["mpi_ranks"] = ranks;
  run["participants"]["dem"]["config"]["snapshot"]["contents"] = {"particle_stress", "bonds", "contacts", "walls"};
  run["run"].erase("checkpoint_every");  // a body on many processes writes no checkpoint yet
  if (exchanges > 0) run["run"]["exchanges"] = exchanges;
  const auto path = folder / ("scenario_" + std::to_string(ranks) + ".json");
  std::ofstream(path) << run.dump(1);
  return path;
}

/// Runs `scenario` on `ranks` processes; returns its results file.
std::filesystem::path run_on(const std::string& name, const std::filesystem::path& scenario, int ranks, int exchanges = 0) {
  const auto folder = fresh_directory("mpi_" + name + "_" + std::to_string(ranks));
  const auto path = on_ranks(scenario, ranks, folder, exchanges);
  const CommandResult result = run_command({coupler(), "run", path.string(), "--out", (folder / "run").string(), "--no-progress"},
                                           std::chrono::seconds(900));
  EXPECT_EQ(result.exit_status, 0) << result.output;
  return folder / "run" / "results.h5";
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// Rows of `values` (width per row) in the order of their ids.
std::vector<double> by_id(const std::vector<double>& values, const std::vector<std::int64_t>& ids) {
  std::vector<std::size_t> order(ids.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  const std::size_t width = ids.empty() ? 0 : values.size() / ids.size();
  std::vector<double> out;
  out.reserve(values.size());
  for (const std::size_t i : order) out.insert(out.end(), values.begin() + std::ptrdiff_t(i * width), values.begin() + std::ptrdiff_t((i + 1) * width));
  return out;
}

/// The rows of a snapshot's pair arrays (bond_* or contact_*), each its two
/// particles' ids then the values of `columns` (i64 columns as doubles), in
/// the order of the ids.
std::vector<std::vector<double>> pair_rows(const h5::File& file, const std::string& group, const std::string& index_array,
                                           const std::vector<std::string>& columns) {
  const auto ids = file.root().open_dataset(group + "particle_id").read_i64();
  const auto index = file.root().open_dataset(group + index_array).read_i64();
  std::vector<std::vector<double>> values;
  for (const std::string& column : columns) {
    const auto dataset = file.root().open_dataset(group + column);
    if (column == "bond_state" || column == "bond_particle_id") {
      const auto v = dataset.read_i64();
      values.emplace_back(v.begin(), v.end());
    } else {
      values.push_back(dataset.read_f64());
    }
  }
  const std::size_t n = index.size() / 2;
  std::vector<std::pair<std::pair<std::int64_t, std::int64_t>, std::vector<double>>> rows(n);
  for (std::size_t r = 0; r < n; ++r) {
    rows[r].first = {ids.at(std::size_t(index[2 * r])), ids.at(std::size_t(index[2 * r + 1]))};
    for (const auto& v : values) {
      const std::size_t width = v.size() / n;
      rows[r].second.insert(rows[r].second.end(), v.begin() + std::ptrdiff_t(r * width), v.begin() + std::ptrdiff_t((r + 1) * width));
    }
  }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::vector<double>> out;
  for (const auto& [pair, row] : rows) {
    out.push_back({double(pair.first), double(pair.second)});
    out.back().insert(out.back().end(), row.begin(), row.end());
  }
  return out;
}

/// Expects `b`'s rows to be `a`'s to the bit.
void expect_same_rows(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  std::size_t differing = 0;
  for (std::size_t r = 0; r < a.size(); ++r) differing += same_bits(a[r], b[r]) ? 0 : 1;
  EXPECT_EQ(differing, 0U) << what << ": rows that differ, of " << a.size();
}

/// Expects `many` (a run on many processes) to hold the bits of `one`.
void expect_same_run(const std::filesystem::path& one, const std::filesystem::path& many) {
  const auto a = h5::File::open_read_only(one);
  const auto b = h5::File::open_read_only(many);
  const auto columns = h5::list_members(a, "/timeseries");
  ASSERT_EQ(columns, h5::list_members(b, "/timeseries"));
  ASSERT_GT(columns.size(), 10U);
  for (const std::string& column : columns) {
    if (column == "wall_time_s") continue;
    EXPECT_TRUE(same_bits(h5::read_f64(a, "/timeseries/" + column), h5::read_f64(b, "/timeseries/" + column))) << "time series " << column;
  }
  const auto snapshots = h5::list_members(a, "/snapshots/dem");
  ASSERT_EQ(snapshots, h5::list_members(b, "/snapshots/dem"));
  ASSERT_GE(snapshots.size(), 2U);  // the first and the last at least
  for (const std::string& snapshot : snapshots) {
    const std::string group = "/snapshots/dem/" + snapshot + "/";
    const auto ids_a = a.root().open_dataset(group + "particle_id").read_i64();
    const auto ids_b = b.root().open_dataset(group + "particle_id").read_i64();
    ASSERT_EQ(ids_a.size(), ids_b.size()) << group;
    ASSERT_FALSE(ids_a.empty()) << group;
    for (const char* array : {"particle_position", "particle_velocity", "particle_radius", "particle_stress_pa"})
      EXPECT_TRUE(same_bits(by_id(h5::read_f64(a, group + array), ids_a), by_id(h5::read_f64(b, group + array), ids_b))) << group << array;
    ASSERT_EQ(a.root().has(group + "bond_particle_index"), b.root().has(group + "bond_particle_index")) << group;
    if (a.root().has(group + "bond_particle_index")) {
      std::vector<std::string> bond = {"bond_particle_id", "bond_state", "bond_position", "bond_normal_force_n", "bond_shear_force_n", "bond_opening_m"};
      if (a.root().has(group + "bond_damage")) bond.emplace_back("bond_damage");
      const auto rows = pair_rows(a, group, "bond_particle_index", bond);
      expect_same_rows(rows, pair_rows(b, group, "bond_particle_index", bond), group + "bonds");
      // bond_particle_id is the pair the index columns name.
      for (const auto& row : rows) EXPECT_TRUE(row[0] == row[2] && row[1] == row[3]) << group << "bond_particle_id";
    }
    ASSERT_TRUE(a.root().has(group + "contact_particle_index") && b.root().has(group + "contact_particle_index")) << group;
    expect_same_rows(pair_rows(a, group, "contact_particle_index", {"contact_normal_force_n", "contact_force_n"}),
                     pair_rows(b, group, "contact_particle_index", {"contact_normal_force_n", "contact_force_n"}), group + "contacts");
    ASSERT_EQ(a.root().has(group + "profile_sigma_v_pa"), b.root().has(group + "profile_sigma_v_pa")) << group;
    if (a.root().has(group + "profile_sigma_v_pa")) {
      for (const char* array : {"profile_depth_m", "profile_sigma_v_pa", "profile_sigma_h_pa", "profile_k0", "profile_porosity"})
        EXPECT_TRUE(same_bits(h5::read_f64(a, group + array), h5::read_f64(b, group + array))) << group << array;
    }
    if (a.root().has(group + "wall_vertices")) {
      EXPECT_TRUE(same_bits(h5::read_f64(a, group + "wall_vertices"), h5::read_f64(b, group + "wall_vertices"))) << group << "wall_vertices";
    }
  }
}

const std::filesystem::path& bonded_pile_on_one() {
  static const auto results = run_on("bonded_pile", e2e_dir() / "scenarios" / "pile_bonded_restart.json", 1);
  return results;
}

TEST(MpiRanks, BondedCoupledPileOnTwoProcessesHasTheBitsOfOne) {
  const auto many = run_on("bonded_pile", e2e_dir() / "scenarios" / "pile_bonded_restart.json", 2);
  expect_same_run(bonded_pile_on_one(), many);
  // The run must exercise what the decomposition has to get right: broken bonds and a moving pile.
  const auto broken = h5::read_f64(h5::File::open_read_only(many), "/timeseries/dem_bonds_broken_tension");
  const auto pile = h5::read_f64(h5::File::open_read_only(many), "/timeseries/dem_pile_displacement_m");
  EXPECT_GT(broken.back() + h5::read_f64(h5::File::open_read_only(many), "/timeseries/dem_bonds_broken_shear").back(), 0.0);
  EXPECT_GT(pile.back(), 0.0);
}

TEST(MpiRanksLong, BondedCoupledPileOnThreeAndFourProcessesHasTheBitsOfOne) {
  for (const int ranks : {3, 4}) {
    SCOPED_TRACE(std::to_string(ranks) + " processes");
    expect_same_run(bonded_pile_on_one(), run_on("bonded_pile", e2e_dir() / "scenarios" / "pile_bonded_restart.json", ranks));
  }
}

const std::filesystem::path& open_pile_on_one() {
  static const auto results = run_on("open_pile", e2e_dir() / "scenarios" / "open_pile_small.json", 1);
  return results;
}

TEST(MpiRanks, OpenPileSmallVariantOnTwoProcessesHasTheBitsOfOne) {
  const auto many = run_on("open_pile", e2e_dir() / "scenarios" / "open_pile_small.json", 2);
  expect_same_run(open_pile_on_one(), many);
  EXPECT_GT(h5::read_f64(h5::File::open_read_only(many), "/timeseries/dem_pile_plug_particles").back(), 0.0);
}

const std::filesystem::path& graded_generation_on_one() {
  static const auto results = run_on("graded_generation", e2e_dir() / "scenarios" / "centrifuge_generation_graded_small.json", 1);
  return results;
}

// The open pile's and the graded generation's small variants on 3 and 4
// processes: boxes that meet at more than one cut, a halo from several
// neighbours.
TEST(MpiRanksSlow, OpenPileAndGradedGenerationSmallVariantsOnThreeAndFourProcessesHaveTheBitsOfOne) {
  for (const int ranks : {3, 4}) {
    SCOPED_TRACE(std::to_string(ranks) + " processes");
    expect_same_run(open_pile_on_one(), run_on("open_pile", e2e_dir() / "scenarios" / "open_pile_small.json", ranks));
    expect_same_run(graded_generation_on_one(),
                    run_on("graded_generation", e2e_dir() / "scenarios" / "centrifuge_generation_graded_small.json", ranks));
  }
}

// A sample prepared in six walls (radius expansion, confinement, bonds) is
// decomposed where its last rebuild saw it (Simulation::move_to_references):
// its lists, and so its bits, stay the whole body's. 60 exchanges of shearing.
TEST(MpiRanks, TriaxialWallsSmallVariantOnTwoProcessesHasTheBitsOfOne) {
  const auto scenario = e2e_dir() / "scenarios" / "triaxial_walls_small.json";
  const auto many = run_on("triaxial_walls", scenario, 2, 60);
  expect_same_run(run_on("triaxial_walls", scenario, 1, 60), many);
  EXPECT_GT(h5::read_f64(h5::File::open_read_only(many), "/timeseries/dem_axial_strain").back(), 0.0);
}

// Platens seated on a soft-bonded cylinder and closed at a strain rate.
TEST(MpiRanks, UcsSmallVariantOnTwoProcessesHasTheBitsOfOne) {
  const auto scenario = e2e_dir() / "scenarios" / "ucs_softbond_small.json";
  expect_same_run(run_on("ucs", scenario, 1, 60), run_on("ucs", scenario, 2, 60));
}

TEST(MpiRanks, GradedGenerationSmallVariantOnTwoProcessesHasTheBitsOfOne) {
  expect_same_run(graded_generation_on_one(), run_on("graded_generation", e2e_dir() / "scenarios" / "centrifuge_generation_graded_small.json", 2));
}

/// `pid` and every process below it, deepest first (mpiexec starts the DEM's processes under it).
std::vector<pid_t> process_tree(pid_t pid) {
  std::vector<pid_t> tree;
  for (const pid_t child : child_pids(pid))
    for (const pid_t below : process_tree(child)) tree.push_back(below);
  tree.push_back(pid);
  return tree;
}

// A checkpoint written on N processes resumes on M (docs/determinism.md §3):
// the bonded coupled pile on 2 processes, checkpointed at exchange 100 of 200
// and killed (SIGKILL, every process), resumed on 3, has the bits of the run
// on one process that was never interrupted; and a checkpoint of one process
// resumes on 2 alike.
TEST(MpiRanks, KilledOnTwoProcessesAndResumedOnThreeHasTheBitsOfTheUninterruptedRun) {
  namespace fs = std::filesystem;
  const auto scenario_file = e2e_dir() / "scenarios" / "pile_bonded_restart.json";
  const fs::path dir = fresh_directory("mpi_restart");
  const auto scenario_on = [&](int ranks, const fs::path& folder) {
    const CommandResult expanded = run_command({coupler(), "expand", scenario_file.string()}, std::chrono::seconds(60));
    nlohmann::json run = nlohmann::json::parse(expanded.output);
    if (run.is_array()) run = run.at(0);
    run["participants"]["dem"]["mpi_ranks"] = ranks;
    run["participants"]["dem"]["config"]["snapshot"]["contents"] = {"particle_stress", "bonds", "contacts", "walls"};
    run["run"]["checkpoint_every"] = 100;
    run["output"] = {{"directory", folder.string()}};
    const fs::path path = dir / ("scenario_" + std::to_string(ranks) + "_" + folder.filename().string() + ".json");
    std::ofstream(path) << run.dump(1);
    return path;
  };
  const fs::path killed = dir / "killed";
  const fs::path log = dir / "killed.log";
  const pid_t coupler_pid = start_command({coupler(), "run", scenario_on(2, killed).string(), "--no-progress"}, log);
  const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(3);
  while (!fs::exists(killed / "checkpoint/coupler.checkpoint") && std::chrono::steady_clock::now() < until) ::usleep(2'000);
  ASSERT_TRUE(fs::exists(killed / "checkpoint/coupler.checkpoint")) << read_text(log);
  ::kill(coupler_pid, SIGSTOP);  // frozen first, so that it starts nothing new while its servers are killed
  for (const pid_t pid : process_tree(coupler_pid)) ::kill(pid, SIGKILL);
  const int killed_status = wait_command(coupler_pid, std::chrono::seconds(10));
  if (killed_status != 128 + SIGKILL) std::cerr << "note: the run ended (status " << killed_status << ") before it was killed\n";

  const auto resumed = run_command({coupler(), "run", "--resume", killed.string(), scenario_on(3, killed).string(), "--no-progress"},
                                   std::chrono::minutes(5));
  ASSERT_EQ(resumed.exit_status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("after exchange 100"), std::string::npos) << resumed.output;
  expect_same_run(bonded_pile_on_one(), killed / "results.h5");

  // One process's checkpoint (the raw state) resumed on two.
  const fs::path single = dir / "single";
  const auto first = run_command({coupler(), "run", scenario_on(1, single).string(), "--no-progress"}, std::chrono::minutes(5));
  ASSERT_EQ(first.exit_status, 0) << first.output;
  const auto again = run_command({coupler(), "run", "--resume", single.string(), scenario_on(2, single).string(), "--no-progress"},
                                 std::chrono::minutes(5));
  ASSERT_EQ(again.exit_status, 0) << again.output;
  EXPECT_NE(again.output.find("after exchange 100"), std::string::npos) << again.output;
  expect_same_run(bonded_pile_on_one(), single / "results.h5");
}

}  // namespace
}  // namespace dfc::testing
