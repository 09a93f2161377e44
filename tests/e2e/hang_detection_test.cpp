// Hang detection (issue 42 part 4, SPEC.md §9.1): a server stopped mid-run
// (SIGSTOP: a frozen node, a process swapped out) ends the run within seconds,
// naming it, although run.deadline_s is 30 min; so does (1.8) one whose main
// thread deadlocked while its heartbeat thread still answers, once its work
// counter has stood still for run.stall_timeout_s. A slow server that answers
// its heartbeat and progresses is never declared hung, and a server of an
// older minor, which has no heartbeat or no counter, still runs.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/common/hdf5_file.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

/// Sends SIGCONT and SIGKILL to the processes of a test (the coupler until it
/// was waited for, the servers it started) whatever happened to them, so that
/// nothing is left running or stopped when a check fails half-way.
class ProcessReaper {
 public:
  void add(pid_t pid) { pids_.push_back(pid); }
  void forget(pid_t pid) { std::erase(pids_, pid); }
  ~ProcessReaper() {
    for (const pid_t pid : pids_) {
      ::kill(pid, SIGCONT);
      ::kill(pid, SIGKILL);
    }
  }

 private:
  std::vector<pid_t> pids_;
};

/// Starts the short pile (DEM + FDM) in a fresh folder `name` with the run
/// keys `run` patched in, and waits until its exchanges run; the coupler's
/// pid goes to `reaper`. Returns the pid and the folder.
std::pair<pid_t, std::filesystem::path> start_short_pile(const std::string& name, const nlohmann::json& run, ProcessReaper& reaper) {
  const auto dir = fresh_directory(name);
  auto scenario = nlohmann::json::parse(read_text(e2e_dir() / "scenarios/pile_short.json"));
  scenario["run"].update(run);
  const auto scenario_file = dir / "pile.json";
  std::ofstream(scenario_file) << scenario.dump(2);
  const pid_t coupler_pid =
      start_command({coupler(), "run", scenario_file.string(), "--out", (dir / "run").string(), "--no-progress"}, dir / "coupler.log");
  reaper.add(coupler_pid);
  wait_for_exchanges(dir / "coupler.log");  // the coupler prints its plan line before the first exchange
  return {coupler_pid, dir};
}

/// Runs the short pile (DEM + FDM) with deadline_s 1800, stops the server
/// `victim` ("dem_server" or "fdm_server") with SIGSTOP once the exchanges
/// run, and checks that the coupler ends the run within 15 s naming it.
void expect_stopped_server_found(const std::string& slot, const std::string& victim_program) {
  ProcessReaper reaper;
  // 100 000 exchanges: surely stopped mid-run; deadline_s 1800, what long
  // studies need: the deadline alone would wait 30 min.
  const auto [coupler_pid, dir] = start_short_pile("hang_" + slot, {{"exchanges", 100000}, {"deadline_s", 1800}}, reaper);
  const auto log = dir / "coupler.log";
  ::usleep(500'000);  // some exchanges done
  pid_t victim = -1;
  for (const pid_t child : child_pids(coupler_pid)) {
    reaper.add(child);
    if (process_name(child).find(victim_program) != std::string::npos) victim = child;
  }
  ASSERT_GT(victim, 0) << "no " << victim_program << " child found\n" << read_text(log);
  ASSERT_EQ(::kill(victim, SIGSTOP), 0);

  const auto stopped_at = std::chrono::steady_clock::now();
  const int status = wait_command(coupler_pid, std::chrono::seconds(30));
  reaper.forget(coupler_pid);  // waited for: its pid is free again
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - stopped_at).count();
  const std::string output = read_text(log);
  EXPECT_LT(seconds, 15.0) << output;
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("server " + slot + " (" + victim_program + ", pid " + std::to_string(victim) + ") stopped answering"), std::string::npos)
      << output;
  EXPECT_NE(output.find("no pong from its heartbeat"), std::string::npos) << output;

  // As for a dead server: the exchanges done are in the file, with the reason.
  const auto file = h5::File::open_read_only(dir / "run/results.h5");
  EXPECT_GE(h5::read_f64(file, "/timeseries/exchange").size(), 1u);
  EXPECT_NE(h5::read_string_attribute(file, "/", "failure").find("stopped answering"), std::string::npos);
}

TEST(HangDetection, StoppedDemServerIsNamedWithinSeconds) { expect_stopped_server_found("dem", "dem_server"); }

TEST(HangDetection, StoppedContinuumServerIsNamedWithinSeconds) { expect_stopped_server_found("continuum", "fdm_server"); }

// A batch system that suspends a job stops all its processes (Slurm's
// `scontrol suspend`: SIGSTOP) and continues them later (SIGCONT). The
// coupler did not run while its servers did not answer: the pause is no
// hang, and the run completes.
TEST(HangDetection, AWholeJobSuspendedAndContinuedCompletes) {
  ProcessReaper reaper;
  // 900 exchanges, about 5 s (the pile meets the floor after about 1 000).
  const auto [coupler_pid, dir] = start_short_pile("hang_whole_job", {{"exchanges", 900}, {"hang_timeout_s", 1}, {"stall_timeout_s", 1}}, reaper);
  const auto log = dir / "coupler.log";
  ::usleep(300'000);
  std::vector<pid_t> job{coupler_pid};
  for (const pid_t child : child_pids(coupler_pid)) {
    reaper.add(child);
    job.push_back(child);
  }
  ASSERT_GE(job.size(), 3u) << read_text(log);  // the coupler and its two servers
  for (const pid_t pid : job) ASSERT_EQ(::kill(pid, SIGSTOP), 0);
  ::sleep(4);  // four silence and stall timeouts
  for (auto pid = job.rbegin(); pid != job.rend(); ++pid) ASSERT_EQ(::kill(*pid, SIGCONT), 0);  // the servers first

  const int status = wait_command(coupler_pid, std::chrono::seconds(120));
  reaper.forget(coupler_pid);
  const std::string output = read_text(log);
  EXPECT_EQ(status, 0) << output;
  EXPECT_EQ(output.find("stopped answering"), std::string::npos) << output;
  const auto file = h5::File::open_read_only(dir / "run/results.h5");
  EXPECT_EQ(h5::read_f64(file, "/timeseries/exchange").size(), 900u);  // every exchange, as if never suspended
}

/// A continuum-only run of the conformance fixture: `config` its section, `args` its options.
CommandResult run_fixture(const std::string& name, const nlohmann::json& config, const nlohmann::json& args, const nlohmann::json& run) {
  const auto dir = fresh_directory(name);
  const nlohmann::json scenario = {{"schema_version", 1},
                                   {"name", name},
                                   {"participants", {{"continuum", {{"program", "conformance_fixture_server"}, {"args", args}, {"config", config}}}}},
                                   {"run", run}};
  std::ofstream(dir / "scenario.json") << scenario.dump(2);
  return run_command({coupler(), "run", (dir / "scenario.json").string(), "--out", (dir / "out").string(), "--no-progress"},
                     std::chrono::seconds(30));
}

// An advance of 3 s, three times run.hang_timeout_s: the server's heartbeat
// answers while its main thread works, so the run completes.
TEST(HangDetection, SlowAdvanceAnsweringItsHeartbeatIsNotHung) {
  const CommandResult result = run_fixture("hang_slow_advance", {{"side", 2}, {"interface", false}, {"advance_s", 3.0}}, nlohmann::json::array(),
                                           {{"exchanges", 1}, {"deadline_s", 30}, {"hang_timeout_s", 1}});
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_GE(result.seconds, 3.0) << result.output;
  EXPECT_EQ(result.output.find("stopped answering"), std::string::npos) << result.output;
}

// A main thread blocked for good inside an advance while the heartbeat thread
// answers: before 1.8 only the deadline (30 min here) found it; now its pongs'
// progress stands still and the run ends after run.stall_timeout_s, naming it.
TEST(HangDetection, DeadlockedMainThreadIsNamedWithinTheStallTimeout) {
  const CommandResult result = run_fixture("hang_deadlock", {{"side", 2}, {"interface", false}}, {"--break", "deadlock-advance"},
                                           {{"exchanges", 3}, {"deadline_s", 1800}, {"stall_timeout_s", 2}});
  EXPECT_EQ(result.exit_status, 1) << result.output;
  EXPECT_GE(result.seconds, 2.0) << result.output;
  EXPECT_LT(result.seconds, 10.0) << result.output;  // the stall timeout, a ping interval, start-up and stop
  EXPECT_NE(result.output.find("server continuum (conformance_fixture_server, pid "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("answers but makes no progress while advancing"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("but its progress stood at "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("longer than 2 s without a step, raise run.stall_timeout_s"), std::string::npos) << result.output;  // the fix
  EXPECT_EQ(result.output.find("stopped answering"), std::string::npos) << result.output;  // stalled, not silent
}

// An advance of 3 s, three times run.stall_timeout_s, whose main thread moves
// the work counter every 0.1 s (as a solver's steps do): it is not stalled.
TEST(HangDetection, SlowAdvanceThatProgressesIsNotStalled) {
  const CommandResult result = run_fixture("hang_slow_progressing", {{"side", 2}, {"interface", false}, {"advance_s", 3.0}},
                                           nlohmann::json::array(), {{"exchanges", 1}, {"deadline_s", 30}, {"stall_timeout_s", 1}});
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_GE(result.seconds, 3.0) << result.output;
  EXPECT_EQ(result.output.find("makes no progress"), std::string::npos) << result.output;
}

// A server of protocol 1.7 sends no progress in its pongs: it is held to the
// silence rule alone, so even its deadlocked advance runs to the deadline.
TEST(HangDetection, ServerOfProtocol1_7IsNotHeldToTheStallRule) {
  const CommandResult result = run_fixture("hang_protocol_1_7", {{"side", 2}, {"interface", false}},
                                           {"--protocol-minor", "7", "--break", "deadlock-advance"},
                                           {{"exchanges", 1}, {"deadline_s", 4}, {"stall_timeout_s", 1}});
  EXPECT_EQ(result.exit_status, 1) << result.output;
  EXPECT_GE(result.seconds, 4.0) << result.output;
  EXPECT_NE(result.output.find("server continuum (conformance_fixture_server, pid "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("did not answer while advancing"), std::string::npos) << result.output;  // the deadline's message
  EXPECT_EQ(result.output.find("makes no progress"), std::string::npos) << result.output;
}

// A server of protocol 1.5 announces no heartbeat: only the deadline applies,
// and the run goes as before.
TEST(HangDetection, ServerOfAnOlderMinorWithoutHeartbeatStillRuns) {
  const CommandResult result = run_fixture("hang_older_minor", {{"side", 2}, {"interface", false}, {"advance_s", 1.5}}, {"--protocol-minor", "5"},
                                           {{"exchanges", 1}, {"deadline_s", 30}, {"hang_timeout_s", 0.5}});
  EXPECT_EQ(result.exit_status, 0) << result.output;
}

// A server of protocol 1.0 (SPEC.md §1: no heartbeat, no monitor_units, no
// progress_monitors, checkpoint unknown) still runs with today's coupler.
TEST(HangDetection, ServerOfProtocol1_0StillRuns) {
  const CommandResult result = run_fixture("hang_protocol_1_0", {{"side", 2}, {"interface", false}}, {"--protocol-minor", "0"},
                                           {{"exchanges", 3}, {"deadline_s", 30}});
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_NE(result.output.find("finished: 3 exchanges"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace dfc::testing
