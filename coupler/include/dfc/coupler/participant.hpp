#pragma once
// Participant: one solver of the run, started by the coupler or reached at an
// endpoint, behind a protocol client. Knows how to name itself in errors and
// notices when its process dies while the coupler waits for it.
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

namespace dfc::coupler {

/// A participant died, hung, or broke the protocol. what() is the whole
/// message for the user: which server, what happened, its last stderr lines.
class ParticipantFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Participant {
 public:
  /// Starts the server (or connects to spec.endpoint). Server logs go to `log_dir`.
  Participant(zmq::context_t& context, const ParticipantSpec& spec, const std::filesystem::path& log_dir,
              std::chrono::milliseconds startup_timeout);

  /// hello, then checks the capability the slot needs (SPEC.md §4.1).
  void hello(std::chrono::milliseconds deadline);
  /// Sends the config section; a BAD_CONFIG reply becomes a dfc::ConfigError
  /// whose key path starts at the scenario root (participants.<slot>.config.<key>).
  nlohmann::json configure(std::chrono::milliseconds deadline);

  /// Throws ParticipantFailure if the started process has exited.
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
  /// ParticipantFailure with the full story (rethrows ConfigError/UserError unchanged).
  [[noreturn]] void fail(const std::exception& error, const std::string& doing);

 private:
  ParticipantSpec spec_;
  std::unique_ptr<ChildProcess> process_;
  std::unique_ptr<protocol::SolverClient> client_;
  protocol::SolverClient::Hello hello_;
  nlohmann::json configured_info_;
};

}  // namespace dfc::coupler
