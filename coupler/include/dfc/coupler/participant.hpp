#pragma once
// Participant: one solver of the run, started by the coupler or reached at an
// endpoint, behind a protocol client. Knows how to name itself in errors and
// notices when its process dies while the coupler waits for it.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <zmq.hpp>

#include "dfc/coupler/child_process.hpp"
#include "dfc/coupler/scenario.hpp"
#include "dfc/protocol/client.hpp"
#include "dfc/protocol/run_key_file.hpp"

namespace dfc::coupler {

/// A participant died, hung (stopped answering), or broke the protocol. what() is the whole
/// message for the user: which server, what happened, its last stderr lines.
class ParticipantFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The user asked the run to stop (Ctrl-C, SIGTERM) and the server being
/// waited for did not answer within StopRequest's grace.
class RunInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Ctrl-C while the coupler waits for a server. The waits of the run may go on
/// for kGrace after the request, so that a responsive server finishes the
/// current exchange and the final snapshot; after that every wait ends with
/// RunInterrupted, so a hung server cannot hold the run for its whole deadline
/// (up to 30 min). Shared by the participants of one run: one grace in all.
class StopRequest {
 public:
  static constexpr std::chrono::milliseconds kGrace{500};
  /// `flag` (may be null: never) is set by the signal handler.
  explicit StopRequest(const std::atomic<bool>* flag) : flag_(flag) {}
  [[nodiscard]] bool requested() const noexcept { return flag_ != nullptr && flag_->load(); }
  /// Throws RunInterrupted naming `pending` (what the run is busy with) once the grace has passed.
  void check(const std::string& pending);
  /// From now the waits may go on for `extra` more than the grace: the
  /// checkpoint a stop writes at an exchange boundary, with every server
  /// responsive, gets the run's deadline to finish.
  void grant(std::chrono::milliseconds extra);

 private:
  const std::atomic<bool>* flag_;
  std::optional<std::chrono::steady_clock::time_point> first_seen_;
  std::chrono::milliseconds granted_{0};
};

class Participant {
 public:
  /// Starts the server, naming `run_keys` in its environment (DFC_KEY_FILE,
  /// SPEC.md §2.1; without them hello refuses a started server of 1.7 or
  /// later), or connects to spec.endpoint with spec.key_file's key when the
  /// scenario names one. Server logs go to `log_dir`.
  /// Every wait for it gives up through `stop` (which must outlive this), and,
  /// once it announced a heartbeat (SPEC.md §9.1), when it has answered
  /// neither the request nor a ping for `hang.silence` (run.hang_timeout_s),
  /// or, from 1.8, its pongs' progress stood still for `hang.stall` (run.stall_timeout_s).
  Participant(zmq::context_t& context, const ParticipantSpec& spec, const std::filesystem::path& log_dir,
              std::chrono::milliseconds startup_timeout, protocol::HangTimeouts hang, StopRequest& stop,
              const protocol::RunKeyFile* run_keys = nullptr);

  /// hello, then watches the heartbeat the server announced (none from a server
  /// before 1.6). Refuses a server it started that declares 1.7 or later but
  /// did not take the run's key: it would answer any local process.
  void hello(std::chrono::milliseconds deadline);
  /// Sends the config section; a BAD_CONFIG reply becomes a dfc::ConfigError
  /// whose key path starts at the scenario root (participants.<slot>.config.<key>).
  nlohmann::json configure(std::chrono::milliseconds deadline);

  /// Throws ParticipantFailure if the started process has exited, RunInterrupted
  /// if a stop request's grace has passed. Runs every 100 ms while waiting.
  void check_alive();
  /// Asks for shutdown and waits briefly for a clean exit; kills otherwise. Never throws.
  void stop() noexcept;

  /// "dem (dem_server, pid 1234)".
  [[nodiscard]] std::string label() const;
  [[nodiscard]] const ParticipantSpec& spec() const noexcept { return spec_; }
  [[nodiscard]] const protocol::SolverClient::Hello& info() const noexcept { return hello_; }
  [[nodiscard]] protocol::SolverClient& client() noexcept { return *client_; }
  [[nodiscard]] const nlohmann::json& configured_info() const noexcept { return configured_info_; }
  /// The session's capabilities: configure's info.capabilities when the server
  /// narrowed them there (SPEC.md §4.2), else those of hello_ok.
  [[nodiscard]] bool has(std::string_view capability) const;

  /// Turns an exception thrown while talking to this participant into a
  /// ParticipantFailure with the full story (rethrows ConfigError and RunInterrupted unchanged).
  [[noreturn]] void fail(const std::exception& error, const std::string& doing);

 private:
  ParticipantSpec spec_;
  StopRequest* stop_;
  zmq::context_t* context_;
  protocol::HangTimeouts hang_;
  bool hung_ = false;  ///< it stopped answering or making progress: stop() kills it at once
  bool authenticated_ = false;  ///< connected with the server's key (SPEC.md §2.1)
  bool greeted_ = false;        ///< hello was answered
  std::unique_ptr<ChildProcess> process_;
  std::unique_ptr<protocol::SolverClient> client_;
  protocol::SolverClient::Hello hello_;
  nlohmann::json configured_info_;
};

}  // namespace dfc::coupler
