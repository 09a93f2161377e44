#pragma once
// Context: the server under test and what the checks have learned about it
// (its limits, capabilities, interface size and step), shared by the checks
// of one run in table order.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "check.hpp"
#include "dfc/common/subprocess.hpp"
#include "dfc/common/temporary_folder.hpp"
#include "dfc/protocol/client.hpp"
#include "dfc/protocol/run_key_file.hpp"
#include "options.hpp"

namespace dfc::conformance {

/// The server process exited while a reply was awaited.
class ServerGone : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Lines of a server's stderr shown after a failure.
inline constexpr std::size_t kStderrTailLines = 20;

class Context {
 public:
  explicit Context(Options options);

  [[nodiscard]] const Options& options() const noexcept { return options_; }
  [[nodiscard]] std::chrono::milliseconds timeout() const noexcept { return options_.timeout; }

  /// Starts COMMAND ARGS --bind tcp://127.0.0.1:* with DFC_KEY_FILE naming the
  /// checker's key file (SPEC.md §2.1), reads the listening line (and the
  /// authentication line before it) and connects, with the key when the
  /// server announced that it authenticates. Throws CheckFailure saying what went wrong.
  void start_server();
  [[nodiscard]] Subprocess& server();
  [[nodiscard]] bool server_started() const noexcept { return server_ != nullptr; }
  [[nodiscard]] const std::string& endpoint() const noexcept { return endpoint_; }
  /// For connections of a check's own (the heartbeat's, SPEC.md §9.1).
  [[nodiscard]] zmq::context_t& zmq_context() noexcept { return zmq_context_; }
  /// Whether the server printed "DFC-AUTHENTICATION curve" (SPEC.md §2.1).
  [[nodiscard]] bool authenticated() const noexcept { return authenticated_; }
  /// The key a connection of a check's own needs: the server's public key
  /// when it authenticates, else none.
  [[nodiscard]] std::optional<std::string> server_key() const;
  /// A folder of the checker's own (mode 0700, removed when it ends) for the
  /// files the checks have the server write or read (checkpoints, SPEC.md §4.7).
  [[nodiscard]] const std::filesystem::path& scratch_folder() const noexcept { return folder_.path(); }

  /// One request with the run's deadline; its seq is assigned by the connection.
  /// Returns error replies (never throws RemoteError). Throws TimeoutError or ServerGone.
  protocol::Message request(protocol::Message request);
  protocol::Message request(std::string_view type, nlohmann::json body = nlohmann::json::object());
  /// Sends hand-made frames (malformed-message checks); returns the reply.
  protocol::Message send_frames(const std::vector<std::string>& frames);
  /// A header object for hand-made frames, with a seq of its own (reply_to can be checked).
  [[nodiscard]] nlohmann::json raw_header(std::string_view type);
  [[nodiscard]] std::int64_t last_raw_seq() const noexcept { return next_raw_seq_ - 1; }

  /// Throws CheckFailure unless the server answers ping with pong.
  void expect_alive();
  /// While set, the server exiting is expected (after shutdown) and not an error.
  void set_exit_expected(bool expected) noexcept { exit_expected_ = expected; }

  // What the checks learned, for the checks after them.
  protocol::Limits limits;               ///< as announced in hello_ok
  bool provides_interface = false;       ///< capabilities from hello_ok
  bool accepts_interface = false;
  bool snapshot = false;
  bool checkpoint = false;               ///< 1.3 (SPEC.md §4.7)
  double dt = 1e-6;                      ///< s; dt_suggested from configured
  std::optional<double> dt_max;          ///< s; configured.info.dt_max when a number
  std::int64_t step = 0;                 ///< the server's step as the checks know it
  nlohmann::json monitor_units;          ///< configured.info.monitor_units; null when the server declared none
  nlohmann::json configured_info;        ///< configured.info as received
  /// Rows of the interface arrays, once known: the mesh the server provided
  /// (get_interface) and the test mesh it accepted (set_interface).
  std::optional<std::int64_t> provided_nodes;
  std::vector<double> provided_coordinates;   ///< [n, 3] of get_interface
  std::vector<std::int64_t> provided_facets;  ///< [m, 3] of get_interface
  std::optional<std::int64_t> accepted_nodes;
  std::optional<protocol::Message> hello_reply;
  /// The minor version hello_ok declares (protocol_version "1.N"); checks of
  /// later rules are skipped (Check::since_minor). Unknown before hello_ok.
  std::optional<int> declared_minor;

  // Bookkeeping of the runner.
  std::set<Milestone> reached;
  std::optional<std::string> unavailable;  ///< why the server can no longer be used, once it cannot
  bool needs_fresh_server = false;         ///< a check failed: the next one starts from a fresh server
  std::string replaced_stderr_tail;        ///< the stderr tail of the last process replaced after a failure

 private:
  void check_still_running();

  Options options_;
  /// The key file every server of this run is started with and the checks'
  /// scratch files, in a folder of the checker's own (removed with it, on
  /// every path out: nothing is left in the system's temporary folder).
  TemporaryFolder folder_{"dfc-conformance-"};
  protocol::RunKeyFile run_keys_;
  bool authenticated_ = false;
  zmq::context_t zmq_context_{1};
  std::optional<protocol::Connection> connection_;
  std::unique_ptr<Subprocess> server_;
  std::string endpoint_;
  std::int64_t next_raw_seq_ = 1'000'000;  ///< far from the connection's own 1, 2, 3 ...
  bool exit_expected_ = false;
};

}  // namespace dfc::conformance
