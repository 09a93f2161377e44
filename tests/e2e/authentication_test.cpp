// Authentication (issue 42 part 1, SPEC.md §2.1): only the run's own
// processes can talk to its servers. The coupler hands the servers it starts
// a key file of its own per run, private by its mode and named in their
// environment, never on a command line; strangers hammering every socket of
// the servers get no answer and do not slow the run; a server started by hand
// is reached with the key file the scenario names.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/client.hpp"
#include "dfc/protocol/key_file.hpp"
#include "e2e_paths.hpp"

namespace dfc::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

mode_t permissions_of(const fs::path& path) {
  struct stat status {};
  return ::lstat(path.c_str(), &status) == 0 ? status.st_mode & 07777 : 0;
}

/// The TCP ports `pid` listens on: its sockets' inodes (/proc/PID/fd) looked
/// up among the listening sockets of /proc/PID/net/tcp (state 0A).
std::vector<int> listening_ports(pid_t pid) {
  const std::string proc = "/proc/" + std::to_string(pid);
  std::set<std::string> inodes;
  std::error_code ec;
  for (const auto& fd : fs::directory_iterator(proc + "/fd", ec)) {
    const std::string target = fs::read_symlink(fd.path(), ec).string();
    if (target.starts_with("socket:[")) inodes.insert(target.substr(8, target.size() - 9));
  }
  std::vector<int> ports;
  std::istringstream table(file_text(proc + "/net/tcp"));
  std::string line;
  std::getline(table, line);  // the header
  while (std::getline(table, line)) {
    std::istringstream fields(line);
    std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout, inode;
    fields >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >> timeout >> inode;
    if (state == "0A" && inodes.contains(inode)) ports.push_back(std::stoi(local.substr(local.find(':') + 1), nullptr, 16));
  }
  return ports;
}

/// Strangers on every endpoint, until stopped: clients without a key and with
/// another key connect anew, ping and wait for an answer, over and over.
class Strangers {
 public:
  explicit Strangers(std::vector<std::string> endpoints) : endpoints_(std::move(endpoints)) {
    for (const bool with_other_key : {false, true}) threads_.emplace_back([this, with_other_key] { hammer(with_other_key); });
  }
  ~Strangers() { stop(); }
  void stop() {
    stop_ = true;
    for (auto& thread : threads_)
      if (thread.joinable()) thread.join();
  }
  [[nodiscard]] int attempts() const { return attempts_; }
  [[nodiscard]] int answers() const { return answers_; }

 private:
  void hammer(bool with_other_key) {
    zmq::context_t context(1);
    while (!stop_) {
      for (const auto& endpoint : endpoints_) {
        const std::optional<std::string> key =
            with_other_key ? std::optional(protocol::authentication::generate_key_pair().public_key) : std::nullopt;
        protocol::Connection connection(context, endpoint, "a stranger", protocol::Limits{}, key);
        protocol::Message ping;
        ping.type = "ping";
        ++attempts_;
        try {
          (void)connection.request_raw(std::move(ping), 20ms);
          ++answers_;
        } catch (const protocol::TimeoutError&) {
          // refused, as it must be
        }
      }
    }
  }

  std::vector<std::string> endpoints_;
  std::atomic<bool> stop_{false};
  std::atomic<int> attempts_{0};
  std::atomic<int> answers_{0};
  std::vector<std::thread> threads_;
};

nlohmann::json pile_scenario(int exchanges) {
  auto scenario = nlohmann::json::parse(read_text(e2e_dir() / "scenarios/pile_short.json"));
  scenario["run"]["exchanges"] = exchanges;
  return scenario;
}

double run_seconds(const fs::path& dir, const nlohmann::json& scenario) {
  std::ofstream(dir / "pile.json") << scenario.dump(2);
  const auto result = run_command({coupler(), "run", (dir / "pile.json").string(), "--out", (dir / "run").string(), "--no-progress"}, 120s);
  EXPECT_EQ(result.exit_status, 0) << result.output;
  return result.seconds;
}

// The coupled pile (DEM + FDM): while it runs, its key file is private, the
// servers' command lines hold no key, and strangers on all four sockets (two
// main, two heartbeats) get no answer; the run ends about as fast as one
// without them. The bound (three times its time and two seconds) leaves room
// for a shared 2-core machine and the strangers' own handshakes; a server
// stalled by them would end the run after run.hang_timeout_s (10 s) instead.
TEST(Authentication, StrangersGetNoAnswerAndDoNotSlowTheRun) {
  const int exchanges = 1000;  // the pile reaches its end (an unstable overlap) near 1050
  const double undisturbed = run_seconds(fresh_directory("authentication_undisturbed"), pile_scenario(exchanges));

  const auto dir = fresh_directory("authentication_strangers");
  std::ofstream(dir / "pile.json") << pile_scenario(exchanges).dump(2);
  const auto log = dir / "coupler.log";
  const auto started = std::chrono::steady_clock::now();
  const pid_t coupler_pid = start_command({coupler(), "run", (dir / "pile.json").string(), "--out", (dir / "run").string(), "--no-progress"}, log);
  wait_for_exchanges(log);

  const fs::path key_file = dir / "run/keys/server.key";
  EXPECT_EQ(permissions_of(dir / "run/keys"), 0700u);
  EXPECT_EQ(permissions_of(key_file), 0600u);
  const auto keys = protocol::read_key_file(key_file);
  std::vector<std::string> endpoints;
  const auto servers = child_pids(coupler_pid);
  EXPECT_EQ(servers.size(), 2u);
  for (const pid_t server : servers) {
    const std::string proc = "/proc/" + std::to_string(server);
    const std::string command_line = file_text(proc + "/cmdline");
    EXPECT_EQ(command_line.find(keys.secret_key), std::string::npos) << command_line;
    EXPECT_EQ(command_line.find(keys.public_key), std::string::npos) << command_line;
    EXPECT_EQ(command_line.find("server.key"), std::string::npos) << command_line;
    // Only the path, in the environment (which only the user and root may read).
    EXPECT_NE(file_text(proc + "/environ").find("DFC_KEY_FILE=" + key_file.string()), std::string::npos);
    for (const int port : listening_ports(server)) endpoints.push_back("tcp://127.0.0.1:" + std::to_string(port));
  }
  EXPECT_EQ(endpoints.size(), 4u) << "the main socket and the heartbeat of each server";

  Strangers strangers(endpoints);
  const int status = wait_command(coupler_pid, 120s);
  const double disturbed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  strangers.stop();
  const std::string output = read_text(log);
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("finished: " + std::to_string(exchanges) + " exchanges"), std::string::npos) << output;
  EXPECT_GT(strangers.attempts(), 20);
  EXPECT_EQ(strangers.answers(), 0);
  EXPECT_LT(disturbed, 3.0 * undisturbed + 2.0) << "undisturbed " << undisturbed << " s, with strangers " << disturbed << " s";
  std::cout << "pile of " << exchanges << " exchanges: " << undisturbed << " s alone, " << disturbed << " s with " << strangers.attempts()
            << " stranger attempts, " << strangers.answers() << " answered\n";
  EXPECT_FALSE(fs::exists(key_file)) << "the run's key file is removed when the run ends";
}

/// A continuum-only scenario of the conformance fixture at `participant`.
fs::path fixture_scenario(const fs::path& dir, const nlohmann::json& participant) {
  nlohmann::json continuum = participant;
  continuum["config"] = {{"side", 2}, {"interface", false}};
  const nlohmann::json scenario = {{"schema_version", 1},
                                   {"name", dir.filename().string()},
                                   {"participants", {{"continuum", continuum}}},
                                   {"run", {{"exchanges", 3}, {"deadline_s", 30}}}};
  std::ofstream(dir / "scenario.json") << scenario.dump(2);
  return dir / "scenario.json";
}

CommandResult run_scenario_file(const fs::path& scenario, const fs::path& out) {
  return run_command({coupler(), "run", scenario.string(), "--out", out.string(), "--no-progress"}, 60s);
}

/// The endpoint a server started by hand printed to `log` (its stdout and stderr).
std::string listening_endpoint(const fs::path& log) {
  for (int i = 0; i < 100; ++i) {
    const std::string text = read_text(log);
    if (const auto at = text.find("DFC-LISTENING "); at != std::string::npos && text.find('\n', at) != std::string::npos)
      return text.substr(at + 14, text.find('\n', at) - at - 14);
    std::this_thread::sleep_for(100ms);
  }
  ADD_FAILURE() << "no DFC-LISTENING line in " << log << ":\n" << read_text(log);
  return "";
}

/// Starts the fixture server as a user would, with DFC_KEY_FILE=dir/server.key
/// and `args`; its stdout and stderr go to dir/<name>.log.
pid_t start_server_by_hand(const fs::path& dir, const std::string& name, const std::vector<std::string>& args) {
  std::vector<std::string> argv{(bin_dir() / "conformance_fixture_server").string()};
  argv.insert(argv.end(), args.begin(), args.end());
  ::setenv("DFC_KEY_FILE", (dir / "server.key").c_str(), 1);  // inherited by the server alone: the coupler is started after unsetenv
  const pid_t pid = start_command(argv, dir / (name + ".log"));
  ::unsetenv("DFC_KEY_FILE");
  return pid;
}

// A server started by hand with DFC_KEY_FILE: the run reaches it with the key
// file the scenario names; a scenario that names none gets no answer, and
// the coupler's message says which scenario key to set.
TEST(Authentication, ServerStartedByHandIsReachedWithTheKeyFileTheScenarioNames) {
  const auto dir = fresh_directory("authentication_by_hand");
  const auto keys = run_command({coupler(), "keys", (dir / "server.key").string()}, 10s);
  ASSERT_EQ(keys.exit_status, 0) << keys.output;
  EXPECT_EQ(permissions_of(dir / "server.key"), 0600u);

  const pid_t keyed = start_server_by_hand(dir, "keyed", {});
  const std::string endpoint = listening_endpoint(dir / "keyed.log");
  EXPECT_NE(read_text(dir / "keyed.log").find("DFC-AUTHENTICATION curve"), std::string::npos);
  const auto with_key = run_scenario_file(fixture_scenario(dir, {{"endpoint", endpoint}, {"key_file", "server.key"}}), dir / "with_key");
  EXPECT_EQ(with_key.exit_status, 0) << with_key.output;
  EXPECT_NE(with_key.output.find("finished: 3 exchanges"), std::string::npos) << with_key.output;
  EXPECT_EQ(wait_command(keyed, 10s), 0) << "the coupler's shutdown ends the server";

  const pid_t unnamed = start_server_by_hand(dir, "unnamed", {});
  const std::string other_endpoint = listening_endpoint(dir / "unnamed.log");
  const auto without_key = run_scenario_file(fixture_scenario(dir, {{"endpoint", other_endpoint}}), dir / "without_key");
  ::kill(unnamed, SIGKILL);
  (void)wait_command(unnamed, 10s);
  EXPECT_EQ(without_key.exit_status, 1) << without_key.output;
  EXPECT_NE(without_key.output.find("the scenario does not name in participants.continuum.key_file"), std::string::npos) << without_key.output;
}

// A user's hand-started server of protocol 1.0 knows no key (SPEC.md §2.1):
// a scenario without key_file runs with it, unauthenticated, as before; one
// that names a key file gets no answer, and the message says to remove it.
TEST(Authentication, HandStartedServerOf1_0RunsWithoutKeyFileAndNamesItWhenGivenOne) {
  const auto dir = fresh_directory("authentication_by_hand_1_0");
  ASSERT_EQ(run_command({coupler(), "keys", (dir / "server.key").string()}, 10s).exit_status, 0);

  const pid_t plain = start_server_by_hand(dir, "plain", {"--protocol-minor", "0"});
  const std::string endpoint = listening_endpoint(dir / "plain.log");
  EXPECT_EQ(read_text(dir / "plain.log").find("DFC-AUTHENTICATION"), std::string::npos) << "a 1.0 server ignores DFC_KEY_FILE";
  const auto without_key = run_scenario_file(fixture_scenario(dir, {{"endpoint", endpoint}}), dir / "without_key");
  EXPECT_EQ(without_key.exit_status, 0) << without_key.output;
  EXPECT_EQ(wait_command(plain, 10s), 0);

  const pid_t keyless = start_server_by_hand(dir, "keyless", {"--protocol-minor", "0"});
  const std::string other_endpoint = listening_endpoint(dir / "keyless.log");
  const auto with_key = run_scenario_file(fixture_scenario(dir, {{"endpoint", other_endpoint}, {"key_file", "server.key"}}), dir / "with_key");
  ::kill(keyless, SIGKILL);
  (void)wait_command(keyless, 10s);
  EXPECT_EQ(with_key.exit_status, 1) << with_key.output;
  EXPECT_NE(with_key.output.find("or it does not hold the key of participants.continuum.key_file"), std::string::npos) << with_key.output;
  EXPECT_NE(with_key.output.find("(then remove key_file)"), std::string::npos) << with_key.output;
}

// The coupler refuses a server it started that declares 1.7 but ignores
// DFC_KEY_FILE: such a server would answer any process on the host.
TEST(Authentication, CouplerRefusesAServerOf1_7ThatIgnoresTheKey) {
  const auto dir = fresh_directory("authentication_ignored");
  const auto result = run_scenario_file(
      fixture_scenario(dir, {{"program", "conformance_fixture_server"}, {"args", {"--break", "no-authentication"}}}), dir / "out");
  EXPECT_EQ(result.exit_status, 1) << result.output;
  EXPECT_NE(result.output.find("did not take the run's key from DFC_KEY_FILE"), std::string::npos) << result.output;
}

// A key file that others may read is refused before any server starts, naming the scenario key and the fix.
TEST(Authentication, ScenarioKeyFileThatOthersMayReadIsRefused) {
  const auto dir = fresh_directory("authentication_open_key");
  ASSERT_EQ(run_command({coupler(), "keys", (dir / "server.key").string()}, 10s).exit_status, 0);
  fs::permissions(dir / "server.key", fs::perms::group_read, fs::perm_options::add);
  const auto result = run_scenario_file(fixture_scenario(dir, {{"endpoint", "tcp://127.0.0.1:9"}, {"key_file", "server.key"}}), dir / "out");
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("participants.continuum.key_file"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("chmod 600"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace dfc::testing
