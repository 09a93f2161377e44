// Exact restart (docs/checkpoints.md): a bonded coupled pile run killed with
// SIGKILL (every process) after a checkpoint and resumed gives the same bits
// as the run that was never interrupted: every time-series column but the
// wall time, and every snapshot (the last one after the resumed exchanges).
// The scenario is built so that, between the checkpoint and the end,
// neighbour lists are rebuilt and bonds break (asserted from the monitors),
// so the contact order and the bond history must survive the restart.
// Also: resuming with another scenario is refused naming the changed key.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

namespace fs = std::filesystem;
constexpr std::int64_t kCheckpointAt = 100;  // of 200 exchanges: one checkpoint only (the last exchange writes none)

hid_t native(const std::string& dtype) {
  if (dtype == "f64") return H5T_NATIVE_DOUBLE;
  if (dtype == "i64") return H5T_NATIVE_INT64;
  if (dtype == "f32") return H5T_NATIVE_FLOAT;
  if (dtype == "i32") return H5T_NATIVE_INT32;
  return H5T_NATIVE_UINT8;
}

/// Every time-series column but wall_time_s, and every snapshot array, compared byte for byte.
void expect_same_bits(const fs::path& expected_file, const fs::path& actual_file) {
  const auto expected = h5::File::open_read_only(expected_file);
  const auto actual = h5::File::open_read_only(actual_file);
  const auto columns = h5::list_members(expected, "/timeseries");
  ASSERT_EQ(columns, h5::list_members(actual, "/timeseries"));
  for (const std::string& column : columns) {
    if (column == "wall_time_s") continue;
    const auto a = expected.root().open_dataset("/timeseries/" + column).read_raw(H5T_NATIVE_DOUBLE);
    const auto b = actual.root().open_dataset("/timeseries/" + column).read_raw(H5T_NATIVE_DOUBLE);
    EXPECT_TRUE(a == b) << "time series column " << column << " differs";
  }
  const auto roles = h5::list_members(expected, "/snapshots");
  ASSERT_EQ(roles, h5::list_members(actual, "/snapshots"));
  for (const std::string& role : roles) {
    const auto snapshots = h5::list_members(expected, "/snapshots/" + role);
    ASSERT_EQ(snapshots, h5::list_members(actual, "/snapshots/" + role)) << role;
    for (const std::string& snapshot : snapshots) {
      const std::string group = "/snapshots/" + role + "/" + snapshot;
      for (const std::string& array : h5::list_members(expected, group)) {
        const h5::Dataset a = expected.root().open_dataset(group + "/" + array);
        const h5::Dataset b = actual.root().open_dataset(group + "/" + array);
        const auto x = a.read_raw(native(a.element_type_name()));
        const auto y = b.read_raw(native(a.element_type_name()));
        // Bytes compared with ==, not memcmp: an empty array's data() is null, and memcmp(nullptr, ...) is undefined (UBSan).
        EXPECT_TRUE(a.shape() == b.shape() && x == y)
            << group << "/" << array << " differs";
      }
    }
  }
}

TEST(ExactRestart, KilledAfterCheckpointAndResumedGivesTheSameBits) {
  const auto dir = fresh_directory("restart_exact");
  const fs::path scenario_file = e2e_dir() / "scenarios/pile_bonded_restart.json";

  // 1. The uninterrupted run, without checkpoints: writing them must not change a bit either.
  const auto uninterrupted = run_command({coupler(), "run", scenario_file.string(), "--out", (dir / "uninterrupted").string(), "--no-progress"},
                                     std::chrono::minutes(5));
  ASSERT_EQ(uninterrupted.exit_status, 0) << uninterrupted.output;

  // 2. The same run with a checkpoint at exchange 100, killed (SIGKILL, all processes) once it is written.
  // Its folder is named by output.directory (not --out), so the run's record
  // DIR/scenario.json names its own folder: resuming from it must be accepted.
  const fs::path run = dir / "killed";
  auto scenario = nlohmann::json::parse(read_text(scenario_file));
  scenario["run"]["checkpoint_every"] = kCheckpointAt;
  scenario["output"]["directory"] = run.string();
  const fs::path checkpointed_file = dir / "checkpointed.json";
  std::ofstream(checkpointed_file) << scenario.dump(2);
  const fs::path log = dir / "killed.log";
  const pid_t coupler_pid = start_command({coupler(), "run", checkpointed_file.string(), "--no-progress"}, log);
  const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(3);
  while (!fs::exists(run / "checkpoint/coupler.checkpoint") && std::chrono::steady_clock::now() < until) ::usleep(2'000);
  ASSERT_TRUE(fs::exists(run / "checkpoint/coupler.checkpoint")) << read_text(log);
  ::kill(coupler_pid, SIGSTOP);  // frozen first, so it starts nothing new while its servers are killed
  const auto servers = child_pids(coupler_pid);
  for (const pid_t server : servers) ::kill(server, SIGKILL);
  ::kill(coupler_pid, SIGKILL);
  const int killed_status = wait_command(coupler_pid, std::chrono::seconds(10));
  // Killed mid-run as intended, unless this machine ran the last 100 exchanges faster than the poll: the resume is tested either way.
  if (killed_status != 128 + SIGKILL) std::cerr << "note: the run ended (status " << killed_status << ") before it was killed\n";

  // 3. Resuming with another scenario is refused, naming the key that changed.
  auto changed = scenario;
  changed["run"]["deadline_s"] = 61;
  const fs::path changed_file = dir / "changed.json";
  std::ofstream(changed_file) << changed.dump(2);
  const auto refused = run_command({coupler(), "run", changed_file.string(), "--resume", run.string(), "--no-progress"}, std::chrono::minutes(2));
  EXPECT_EQ(refused.exit_status, 2) << refused.output;
  EXPECT_NE(refused.output.find("/run/deadline_s"), std::string::npos) << refused.output;

  // 4. Resumed from the checkpoint into the same results file.
  const auto resumed = run_command({coupler(), "run", "--resume", run.string(), "--no-progress"}, std::chrono::minutes(5));
  ASSERT_EQ(resumed.exit_status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("after exchange " + std::to_string(kCheckpointAt)), std::string::npos) << resumed.output;

  expect_same_bits(dir / "uninterrupted/results.h5", run / "results.h5");

  // The restart crossed what makes it hard: rebuilds and bond breakage after the checkpoint.
  const auto file = h5::File::open_read_only(dir / "uninterrupted/results.h5");
  const auto broken = h5::read_f64(file, "/timeseries/dem_bonds_broken_tension");
  const auto broken_shear = h5::read_f64(file, "/timeseries/dem_bonds_broken_shear");
  ASSERT_EQ(broken.size(), 200u);
  EXPECT_GT(broken.back() + broken_shear.back(), broken[kCheckpointAt - 1] + broken_shear[kCheckpointAt - 1])
      << "no bond broke after the checkpoint: the scenario no longer tests the bond history";
}

}  // namespace
}  // namespace dfc::testing
