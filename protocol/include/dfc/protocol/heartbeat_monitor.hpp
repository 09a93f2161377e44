#pragma once
// The client's side of the heartbeat (SPEC.md §9.1, 1.6): while a client
// waits for a server's reply it pings the server's heartbeat endpoint on a
// socket of its own; a server that answers neither the request nor any ping
// for the hang timeout is hung (stopped, frozen, or its process swapped out),
// however long its deadline. A server busy in a long advance answers the pings.
// From 1.8 the pongs carry the main thread's work counter: a server whose
// pongs come but whose counter stands still for the stall timeout is hung too
// (its main thread deadlocked or spins while its heartbeat thread answers).
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include <zmq.hpp>

#include <nlohmann/json.hpp>

namespace dfc::protocol {

/// How long a wait tolerates each sign of a hang.
struct HangTimeouts {
  std::chrono::milliseconds silence;  ///< no pong to a ping of this wait (the coupler: run.hang_timeout_s)
  std::chrono::milliseconds stall;    ///< pongs come, but their `progress` stands still (run.stall_timeout_s; 1.8 servers)
};

/// What a wait's latest poll found.
enum class Liveliness {
  alive,    ///< answering, and making progress (or not saying: a server before 1.8)
  silent,   ///< no pong for the silence timeout
  stalled,  ///< pongs, but the same `progress` for the stall timeout
};

class HeartbeatMonitor {
 public:
  /// Connects a DEALER socket to the heartbeat at `endpoint`, with the
  /// server's key when it has one (SPEC.md §2.1). Both timeouts > 0.
  HeartbeatMonitor(zmq::context_t& context, const std::string& endpoint, HangTimeouts timeouts, const std::optional<std::string>& server_key);

  /// A wait for a reply begins: the silence is counted from now (the last
  /// reply, or the client's own work, came just before), the stall from the
  /// first pong of this wait that carries `progress`.
  void begin_wait();
  /// Sends a ping when one is due (every second, or a quarter of the silence
  /// timeout if that is shorter, from one interval into the wait) and reads
  /// the pongs that arrived. Expects to be called far more often than half the
  /// silence timeout: a longer gap since the previous poll means the client was
  /// paused (the whole job stopped and continued), and that gap counts neither
  /// as silence nor as stall. Alive while a pong to a ping of this wait came
  /// less than the silence timeout ago (or the wait is younger than that)
  /// and, for a server whose pongs carry `progress`, while it changed less
  /// than the stall timeout ago.
  [[nodiscard]] Liveliness poll();

  /// "no pong from its heartbeat (tcp://127.0.0.1:40124) for 10.0 s; the last one
  /// said 57 requests handled, step 1200, busy for 3.1 s".
  [[nodiscard]] std::string silence_description() const;
  /// "its heartbeat (tcp://127.0.0.1:40124) answers, but its progress stood at
  /// 8812 for 120.0 s; the last pong said 57 requests handled, step 1200, busy for 130.2 s".
  [[nodiscard]] std::string stall_description() const;
  [[nodiscard]] const HangTimeouts& timeouts() const noexcept { return timeouts_; }
  [[nodiscard]] const std::string& endpoint() const noexcept { return endpoint_; }

 private:
  using Clock = std::chrono::steady_clock;
  void read_pongs(Clock::time_point now);
  /// "; the last one said 57 requests handled, step 1200, busy for 3.1 s" (`pong`: "one" or "pong").
  [[nodiscard]] std::string last_pong_account(const std::string& pong) const;

  zmq::socket_t socket_;
  std::string endpoint_;
  HangTimeouts timeouts_;
  std::chrono::milliseconds interval_;
  std::int64_t next_seq_ = 1;
  std::int64_t first_seq_of_wait_ = 1;  ///< pongs to earlier pings (of an earlier wait) prove nothing now
  Clock::time_point last_ping_{};
  Clock::time_point last_life_{};       ///< the wait's start or its latest pong
  Clock::time_point last_poll_{};       ///< the previous poll (a longer gap than half the silence: the client was paused)
  std::optional<std::int64_t> progress_;  ///< the latest `progress` a pong of this wait carried; none before 1.8
  Clock::time_point progress_since_{};  ///< when a pong of this wait first carried progress_
  bool ever_answered_ = false;
  nlohmann::json last_pong_body_;       ///< the body of the latest pong, for the message
};

}  // namespace dfc::protocol
