// Defects found by probing the programs from outside (issue 20): each test
// runs the real executables the way the probe did and checks the fix.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

/// The small DEM bed of bed_on_block.json on the fixture continuum, broken in `breakage`.
nlohmann::json dem_on_fixture(const std::string& name, const std::string& breakage) {
  auto scenario = nlohmann::json::parse(read_text(e2e_dir() / "scenarios/bed_on_block.json"));
  scenario["name"] = name;
  scenario["participants"]["continuum"] = {
      {"program", "conformance_fixture_server"}, {"args", {"--break", breakage}}, {"config", {{"side", 3}}}};
  scenario["run"] = {{"exchanges", 3}, {"deadline_s", 30}};
  return scenario;
}

/// The conformance fixture alone, broken in `breakage`, for `exchanges` exchanges.
nlohmann::json fixture_alone(const std::string& name, const std::string& breakage, int exchanges) {
  return {{"schema_version", 1},
          {"name", name},
          {"participants",
           {{"continuum", {{"program", "conformance_fixture_server"}, {"args", {"--break", breakage}}, {"config", {{"side", 3}}}}}}},
          {"run", {{"exchanges", exchanges}}}};
}

std::filesystem::path write_scenario(const std::filesystem::path& dir, const nlohmann::json& scenario) {
  const auto file = dir / (scenario.at("name").get<std::string>() + ".json");
  std::ofstream(file) << scenario.dump(2);
  return file;
}

/// Runs the DEM bed on the fixture continuum broken in `breakage`, 3 exchanges.
CommandResult run_dem_on_fixture(const std::string& breakage) {
  const std::string name = "dem_on_" + breakage;
  const auto dir = fresh_directory("probe_" + name);
  const auto file = write_scenario(dir, dem_on_fixture(name, breakage));
  return run_command({coupler(), "run", file.string(), "--out", (dir / "out").string(), "--no-progress"}, std::chrono::seconds(120));
}

/// Runs `argv` through sh with only the stream `keep` (1 stdout, 2 stderr) kept.
CommandResult run_keeping_stream(const std::vector<std::string>& argv, int keep) {
  std::string command;
  for (const auto& arg : argv) command += "'" + arg + "' ";
  command += keep == 1 ? "2>/dev/null" : "2>&1 >/dev/null";
  return run_command({"/bin/sh", "-c", command}, std::chrono::seconds(60));
}

// Item 7: Ctrl-C while a server hangs waited for the whole deadline (62 s,
// 30 min with deadline_s 1800); it must end the run within 2 s.
TEST(ProbedDefects, CtrlCEndsARunWithAHungServerWithinTwoSeconds) {
  const auto dir = fresh_directory("probe_ctrl_c");
  nlohmann::json scenario = fixture_alone("hang_ctrl_c", "hang", 5);
  scenario["run"]["deadline_s"] = 1800;  // the shipped value: Ctrl-C waited for all of it
  const auto log = dir / "coupler.log";
  const pid_t coupler_pid =
      start_command({coupler(), "run", write_scenario(dir, scenario).string(), "--out", (dir / "out").string(), "--no-progress"}, log);
  wait_for_exchanges(log);
  ::usleep(300'000);  // the first advance is now hanging
  ASSERT_EQ(::kill(coupler_pid, SIGINT), 0);
  const auto interrupted_at = std::chrono::steady_clock::now();
  const int status = wait_command(coupler_pid, std::chrono::seconds(20));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - interrupted_at).count();
  const std::string output = read_text(log);
  EXPECT_LT(seconds, 2.0) << output;
  EXPECT_EQ(status, 130) << output;
  EXPECT_NE(output.find("stopped by a signal"), std::string::npos) << output;
  EXPECT_TRUE(std::filesystem::exists(dir / "out/results.h5")) << output;
}

// Item 4: a program whose DFC-LISTENING line holds no endpoint was an
// "internal error" (exit 1); it is a keyed error (exit 2).
TEST(ProbedDefects, MalformedListeningLineIsAKeyedError) {
  const auto dir = fresh_directory("probe_listening");
  const auto program = dir / "bad_server.sh";
  std::ofstream(program) << "#!/bin/sh\necho 'DFC-LISTENING tcp://127.0.0.1'\nsleep 30\n";
  ::chmod(program.c_str(), 0755);
  const nlohmann::json scenario = {{"schema_version", 1},
                                   {"name", "bad_listening"},
                                   {"participants", {{"continuum", {{"program", program.string()}, {"config", nlohmann::json::object()}}}}},
                                   {"run", {{"exchanges", 1}}}};
  const CommandResult result = run_command({coupler(), "check", write_scenario(dir, scenario).string()}, std::chrono::seconds(30));
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("scenario error at participants.continuum.program"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("internal error"), std::string::npos) << result.output;
}

// Item 10: a continuum that never sends interface_force_received let the
// coupler print "balanced at every exchange (worst relative mismatch 0)".
TEST(ProbedDefects, AnUncheckedForceBalanceIsReportedAsUnchecked) {
  const CommandResult result = run_dem_on_fixture("no-force-monitor");
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_EQ(result.output.find("balanced at every exchange"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("NOT checked at 3 of 3 exchanges"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("interface_force_received"), std::string::npos) << result.output;
}

// Item 10: a NaN velocity from the continuum was passed on, and the DEM was blamed.
TEST(ProbedDefects, NonFiniteContinuumVelocityBlamesTheContinuum) {
  const CommandResult result = run_dem_on_fixture("nan-velocity");
  EXPECT_EQ(result.exit_status, 1) << result.output;
  EXPECT_NE(result.output.find("server continuum (conformance_fixture_server"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("non-finite interface velocity"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("server dem ("), std::string::npos) << result.output;
}

// Item 9: a bed too large to snapshot passed `check` and died with a bare
// std::bad_alloc at the first snapshot; check estimates it, with the key.
TEST(ProbedDefects, ABedTooLargeToSnapshotIsRefusedAtCheckWithItsKey) {
  const auto dir = fresh_directory("probe_huge_bed");
  const nlohmann::json scenario = fixture_alone("huge_bed", "huge-particle-count", 1);
  const CommandResult result = run_command({coupler(), "check", write_scenario(dir, scenario).string()}, std::chrono::seconds(30));
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("scenario error at participants.continuum.config: the model has 20000000000 particles"), std::string::npos)
      << result.output;
}

// A server's malformed info.progress_monitors (SPEC.md §4.2) is found by
// `check`, and fails a run before it writes a results file.
TEST(ProbedDefects, AMalformedProgressMonitorListFailsCheckAndTheRunBeforeAnyResult) {
  const auto dir = fresh_directory("probe_malformed_progress");
  const auto file = write_scenario(dir, fixture_alone("malformed_progress", "malformed-progress-monitors", 3));
  const CommandResult checked = run_command({coupler(), "check", file.string()}, std::chrono::seconds(30));
  EXPECT_EQ(checked.exit_status, 1) << checked.output;
  EXPECT_NE(checked.output.find("info.progress_monitors must be an array"), std::string::npos) << checked.output;
  const CommandResult ran = run_command({coupler(), "run", file.string(), "--out", (dir / "out").string(), "--no-progress"}, std::chrono::seconds(30));
  EXPECT_EQ(ran.exit_status, 1) << ran.output;
  EXPECT_NE(ran.output.find("info.progress_monitors must be an array"), std::string::npos) << ran.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/results.h5")) << ran.output;
}

// Item 13: failures went to stdout and stderr stayed empty.
TEST(ProbedDefects, FailuresArePrintedOnStderr) {
  const auto dir = fresh_directory("probe_stderr");
  const nlohmann::json scenario = fixture_alone("throwing", "throw", 2);
  const auto file = write_scenario(dir, scenario);
  const std::vector<std::string> argv{coupler(), "run", file.string(), "--out", (dir / "out").string(), "--no-progress"};
  const CommandResult stdout_only = run_keeping_stream(argv, 1);
  const CommandResult stderr_only = run_keeping_stream(argv, 2);
  EXPECT_EQ(stderr_only.exit_status, 1) << stderr_only.output;
  EXPECT_NE(stderr_only.output.find("coupler: run 'throwing' stopped"), std::string::npos) << stderr_only.output;
  EXPECT_EQ(stdout_only.output.find("stopped"), std::string::npos) << stdout_only.output;
}

// Item 13: a directory as the scenario was "not valid JSON"; a bad option
// value printed the library's "stod".
TEST(ProbedDefects, ConfusingMessagesSayWhatIsWrong) {
  const auto dir = fresh_directory("probe_messages");
  const CommandResult folder = run_command({coupler(), "check", dir.string()}, std::chrono::seconds(30));
  EXPECT_EQ(folder.exit_status, 2) << folder.output;
  EXPECT_NE(folder.output.find("is a directory"), std::string::npos) << folder.output;
  for (const char* server : {"fdm_server", "dem_server"}) {
    const CommandResult option = run_command({(bin_dir() / server).string(), "--idle-timeout", "abc"}, std::chrono::seconds(30));
    EXPECT_EQ(option.exit_status, 2) << option.output;
    EXPECT_NE(option.output.find("--idle-timeout"), std::string::npos) << option.output;
    EXPECT_EQ(option.output.find("stod"), std::string::npos) << option.output;
  }
}

}  // namespace
}  // namespace dfc::testing
