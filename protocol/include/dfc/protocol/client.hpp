#pragma once
// The client side of protocol v1 (the coupler, the conformance checker):
// one DEALER socket to one server, request/reply with deadlines.
#include <chrono>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "dfc/protocol/codec.hpp"
#include "dfc/protocol/heartbeat_monitor.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::protocol {

/// No reply within the deadline.
class TimeoutError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The server is hung (SPEC.md §9.1): neither a reply nor a heartbeat pong
/// within the silence timeout (silent: stopped or frozen), or pongs whose
/// `progress` stood still for the stall timeout (stalled: its main thread
/// deadlocked or spins while its heartbeat thread answers; servers of 1.8 on).
class HungError : public TimeoutError {
 public:
  enum class Kind { silent, stalled };
  /// what(): "<label> stopped answering: <account>" or "<label> answers but
  /// makes no progress: <account>"; account(): the heartbeat's account alone.
  HungError(const std::string& label, Kind kind, std::string account)
      : TimeoutError(label + (kind == Kind::silent ? " stopped answering: " : " answers but makes no progress: ") + account),
        kind_(kind),
        account_(std::move(account)) {}
  [[nodiscard]] Kind kind() const noexcept { return kind_; }
  [[nodiscard]] const std::string& account() const noexcept { return account_; }

 private:
  Kind kind_;
  std::string account_;
};

/// The server answered with an `error` message.
class RemoteError : public std::runtime_error {
 public:
  RemoteError(std::string code, std::string message, std::string key)
      : std::runtime_error(message), code_(std::move(code)), key_(std::move(key)) {}
  [[nodiscard]] const std::string& code() const noexcept { return code_; }
  [[nodiscard]] const std::string& key() const noexcept { return key_; }

 private:
  std::string code_;
  std::string key_;
};

class Connection {
 public:
  /// Connects a DEALER socket to `endpoint`. `label` names the server in errors.
  /// With `server_key` (the public key of the server's key file) the socket
  /// is a CURVE client (SPEC.md §2.1), and so is the heartbeat's.
  Connection(zmq::context_t& context, const std::string& endpoint, std::string label, Limits limits = {},
             std::optional<std::string> server_key = std::nullopt);

  /// Called about every 100 ms while a reply is awaited; may throw to abort
  /// the wait (the coupler checks there that the server process is alive).
  using WaitHook = std::function<void()>;
  void set_wait_hook(WaitHook hook) { wait_hook_ = std::move(hook); }

  /// From now on every wait pings the server's heartbeat at `endpoint` (SPEC.md
  /// §9.1) and ends with HungError once a ping has gone unanswered for
  /// `timeouts.silence`, or the pongs' progress stood still for
  /// `timeouts.stall`, while no reply came. Without it only the deadline applies.
  void watch_heartbeat(zmq::context_t& context, const std::string& endpoint, HangTimeouts timeouts);
  [[nodiscard]] bool heartbeat_watched() const noexcept { return heartbeat_.has_value(); }

  /// Sends `request` (its seq is assigned here) and returns the reply with the
  /// matching reply_to; stale replies to earlier, abandoned requests are skipped.
  /// Throws TimeoutError, or RemoteError when the reply is an `error`.
  Message request(Message request, std::chrono::milliseconds deadline);

  /// Like request() but returns `error` replies instead of throwing (conformance checks).
  Message request_raw(Message request, std::chrono::milliseconds deadline);

  /// Sends raw frames (for malformed-message checks) and waits for any reply.
  std::optional<Message> send_frames_raw(const std::vector<std::string>& frames, std::chrono::milliseconds deadline);

  [[nodiscard]] const std::string& label() const noexcept { return label_; }

 private:
  std::optional<Message> await_reply(std::optional<std::int64_t> seq, std::chrono::milliseconds deadline);

  zmq::socket_t socket_;
  std::string endpoint_;
  std::optional<std::string> server_key_;
  std::optional<HeartbeatMonitor> heartbeat_;
  std::string label_;
  Limits limits_;
  std::int64_t next_seq_ = 1;
  WaitHook wait_hook_;
  /// reply_to of the replies the last wait skipped (none of them answered its
  /// request): a timeout names them, since a server that answers with a wrong
  /// reply_to looks like one that never answers.
  std::vector<std::int64_t> skipped_reply_to_;
};

/// Typed calls of the lifecycle (SPEC.md §4), on top of Connection.
class SolverClient {
 public:
  /// `server_key`: as for Connection.
  SolverClient(zmq::context_t& context, const std::string& endpoint, std::string label, std::optional<std::string> server_key = std::nullopt);

  struct Hello {
    std::string solver_name;
    std::string solver_version;
    std::string protocol_version;
    std::string role;
    std::vector<std::string> capabilities;
    std::string heartbeat_endpoint;  ///< 1.6 (SPEC.md §9.1); empty when the server announces none
    [[nodiscard]] bool has(std::string_view capability) const;
  };
  Hello hello(const std::string& client_name, std::chrono::milliseconds deadline);
  /// Returns the configured reply's body ({scenario_hash, info}); checks the
  /// hash the server computed equals the hash of the text sent.
  nlohmann::json configure(const std::string& section_json, std::chrono::milliseconds deadline);
  InterfaceMesh get_interface(std::chrono::milliseconds deadline);
  void set_interface(const InterfaceMesh& mesh, std::chrono::milliseconds deadline);
  Message advance(std::int64_t step, std::int64_t n_steps, double dt, std::vector<Array> inputs, std::chrono::milliseconds deadline);
  nlohmann::json query(std::chrono::milliseconds deadline);
  Message snapshot(std::chrono::milliseconds deadline);
  /// The server writes its complete state to `path` (SPEC.md §4.7); returns its step then.
  std::int64_t checkpoint(const std::string& path, std::chrono::milliseconds deadline);
  /// The server (configured, not yet advanced) continues from the file at `path`; returns its step.
  std::int64_t restore(const std::string& path, std::chrono::milliseconds deadline);
  void shutdown(std::chrono::milliseconds deadline);

  Connection& connection() noexcept { return connection_; }

 private:
  Connection connection_;
};

}  // namespace dfc::protocol
