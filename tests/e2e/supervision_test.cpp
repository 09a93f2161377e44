// Supervision (issue check 5): a server killed with SIGKILL mid-run ends the
// run with a non-zero status within 10 s, the message names the server, and
// the HDF5 file opens and holds every exchange completed before the failure.
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

TEST(Supervision, KilledServerEndsRunAndResultsStayReadable) {
  const auto dir = fresh_directory("supervision");
  const auto log = dir / "coupler.log";
  // The split box, made long enough (100 000 exchanges) that it is surely killed mid-run.
  auto scenario = nlohmann::json::parse(read_text(e2e_dir() / "scenarios/box_split.json"));
  scenario["run"]["exchanges"] = 100000;
  const auto scenario_file = dir / "long_split.json";
  std::ofstream(scenario_file) << scenario.dump(2);
  const pid_t coupler_pid = start_command({coupler(), "run", scenario_file.string(), "--out", (dir / "run").string(), "--no-progress"}, log);

  // Wait until the run is under way: the coupler prints its plan line before the first exchange.
  wait_for_exchanges(log);
  ::usleep(700'000);  // let some exchanges complete
  pid_t victim = -1;
  for (const pid_t child : child_pids(coupler_pid))
    if (process_name(child).find("fdm_server") != std::string::npos) victim = child;  // the last started: the continuum
  ASSERT_GT(victim, 0) << "no fdm_server child found\n" << read_text(log);
  ASSERT_EQ(::kill(victim, SIGKILL), 0);

  const auto killed_at = std::chrono::steady_clock::now();
  const int status = wait_command(coupler_pid, std::chrono::seconds(10));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - killed_at).count();
  const std::string output = read_text(log);
  EXPECT_LT(seconds, 10.0);
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("pid " + std::to_string(victim)), std::string::npos) << output;
  EXPECT_NE(output.find("killed by signal 9"), std::string::npos) << output;

  const auto file = h5::File::open_read_only(dir / "run/results.h5");
  const auto exchange = h5::read_f64(file, "/timeseries/exchange");
  ASSERT_GE(exchange.size(), 1u) << "exchanges before the failure must be in the file";
  for (std::size_t i = 0; i < exchange.size(); ++i) EXPECT_EQ(exchange[i], double(i + 1)) << "no exchange may be missing";
  EXPECT_NE(h5::read_string_attribute(file, "/", "failure").find("fdm_server"), std::string::npos);
}

}  // namespace
}  // namespace dfc::testing

namespace dfc::testing {
namespace {

// A server that stops answering (alive but hung) misses run.deadline_s: the
// run ends with status 1 and a message naming the server and what it was doing.
TEST(Supervision, HungServerMissesItsDeadline) {
  const auto dir = fresh_directory("supervision_hang");
  const nlohmann::json scenario = {
      {"schema_version", 1},
      {"name", "hang"},
      {"participants",
       {{"continuum", {{"program", "conformance_fixture_server"}, {"args", {"--break", "hang"}}, {"config", {{"side", 3}}}}}}},
      {"run", {{"exchanges", 5}, {"deadline_s", 2}}}};
  std::ofstream(dir / "hang.json") << scenario.dump(2);
  const CommandResult result =
      run_command({coupler(), "run", (dir / "hang.json").string(), "--out", (dir / "out").string(), "--no-progress"}, std::chrono::seconds(30));
  EXPECT_EQ(result.exit_status, 1) << result.output;
  EXPECT_LT(result.seconds, 10.0);
  EXPECT_NE(result.output.find("server continuum (conformance_fixture_server"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("did not answer while advancing from step 0"), std::string::npos) << result.output;
}

// Connecting to a server that is already running (scenario key `endpoint`
// instead of `program`), e.g. one started by hand or on another host.
TEST(Supervision, ConnectsToARunningServerAtAnEndpoint) {
  const auto dir = fresh_directory("endpoint");
  const pid_t server = start_command({(bin_dir() / "fdm_server").string(), "--bind", "tcp://127.0.0.1:*"}, dir / "server.log");
  std::string endpoint;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (endpoint.empty() && std::chrono::steady_clock::now() < until) {
    const std::string text = read_text(dir / "server.log");
    const auto at = text.find("DFC-LISTENING ");
    if (at != std::string::npos && text.find('\n', at) != std::string::npos)
      endpoint = text.substr(at + 14, text.find('\n', at) - at - 14);
    else
      ::usleep(50'000);
  }
  ASSERT_FALSE(endpoint.empty()) << read_text(dir / "server.log");
  auto scenario = nlohmann::json::parse(read_text(e2e_dir() / "scenarios/box_unsplit.json"));
  auto& continuum = scenario["participants"]["continuum"];
  continuum.erase("program");
  continuum["endpoint"] = endpoint;
  scenario["run"]["exchanges"] = 3;
  std::ofstream(dir / "endpoint.json") << scenario.dump(2);
  const CommandResult result =
      run_command({coupler(), "run", (dir / "endpoint.json").string(), "--out", (dir / "out").string(), "--no-progress"}, std::chrono::seconds(60));
  EXPECT_EQ(result.exit_status, 0) << result.output;
  // The coupler shut the server down at the end of the run: it exits cleanly by itself.
  EXPECT_EQ(wait_command(server, std::chrono::seconds(10)), 0);
  const auto file = h5::File::open_read_only(dir / "out/results.h5");
  EXPECT_EQ(h5::read_f64(file, "/timeseries/exchange").size(), 3u);
}

}  // namespace
}  // namespace dfc::testing
