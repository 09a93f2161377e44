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
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (read_text(log).find("exchanges,") == std::string::npos && std::chrono::steady_clock::now() < until) ::usleep(50'000);
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
