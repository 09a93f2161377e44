#pragma once
// ServerSession: the v1 lifecycle state machine of a server (SPEC.md §5),
// independent of sockets so it can be unit-tested message by message.
//
//   fresh --hello--> greeted --configure--> configured --advance--> running
//   any state --shutdown--> closed;   configured | running --solver failure--> failed
//   (an advance refused for an unstable dt, UnstableStepError, changes nothing)
//   configured --restore--> running (1.3, capability checkpoint)
#include <cstdint>
#include <string>
#include <string_view>

#include "dfc/protocol/codec.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::protocol {

enum class SessionState { fresh, greeted, configured, running, failed, closed };

/// What the solver's own advancing cost, so that the time of an exchange can
/// be split into the solvers' work and the coupling's (bench/exchange_overhead.sh).
struct AdvanceStatistics {
  std::int64_t advances = 0;    ///< successful advance requests
  std::int64_t steps = 0;       ///< solver steps they took
  double solver_seconds = 0.0;  ///< wall time inside SolverBackend::advance
  /// The first advance alone: it carries one-time work (a DEM's first list
  /// build and seam balance), so a short run's mean per advance overstates
  /// the steady cost; the log line also gives the mean of the later ones.
  double first_advance_seconds = 0.0;
};
[[nodiscard]] std::string_view session_state_name(SessionState state) noexcept;

class ServerSession {
 public:
  ServerSession(SolverBackend& backend, Limits limits);

  /// The minor version the session declares in hello_ok and every reply's
  /// header (default kVersionMinor). Only a test fixture that plays an older
  /// server declares less; the session then answers as that server would
  /// where the rules differ (before 1.3, checkpoint and restore are UNKNOWN_TYPE).
  void declare_minor(int minor) {
    minor_ = minor;
    version_ = std::to_string(kVersionMajor) + "." + std::to_string(minor);
  }
  [[nodiscard]] const std::string& version() const noexcept { return version_; }
  /// hello_ok announces the heartbeat's endpoint (SPEC.md §9.1, 1.6) when one is set.
  void set_heartbeat_endpoint(std::string endpoint) { heartbeat_endpoint_ = std::move(endpoint); }

  /// The reply to one decoded request. Never throws: every failure becomes an `error` reply.
  [[nodiscard]] Message handle(const Message& request);
  /// The reply to a message that could not be decoded (SPEC.md §3.1): an
  /// `error` with the session's next seq, like every other reply, and
  /// `reply_to` only when the request's seq could be read.
  [[nodiscard]] Message refuse_undecodable(const DecodeError& error);

  [[nodiscard]] SessionState state() const noexcept { return state_; }
  [[nodiscard]] std::int64_t step() const noexcept { return step_; }
  [[nodiscard]] bool closed() const noexcept { return state_ == SessionState::closed; }
  [[nodiscard]] const AdvanceStatistics& advance_statistics() const noexcept { return advance_statistics_; }

 private:
  Message dispatch(const Message& request);
  Message on_hello(const Message& request);
  Message on_configure(const Message& request);
  Message on_get_interface(const Message& request);
  Message on_set_interface(const Message& request);
  Message on_advance(const Message& request);
  Message on_query(const Message& request);
  Message on_snapshot(const Message& request);
  Message on_checkpoint(const Message& request);
  Message on_restore(const Message& request);
  /// body.path of a checkpoint or restore request, after the capability check (UNSUPPORTED).
  [[nodiscard]] std::string checkpoint_path(const Message& request) const;
  void require_state(const Message& request, std::initializer_list<SessionState> allowed) const;
  Message reply_to(const Message& request, std::string_view type);

  SolverBackend& backend_;
  Limits limits_;
  SessionState state_ = SessionState::fresh;
  std::int64_t step_ = 0;
  std::int64_t next_seq_ = 0;
  std::string section_hash_;  ///< configured.scenario_hash, stamped on checkpoints
  int minor_ = kVersionMinor;
  std::string version_ = version_string();
  std::string heartbeat_endpoint_;  ///< empty: none announced
  AdvanceStatistics advance_statistics_;
};

}  // namespace dfc::protocol
